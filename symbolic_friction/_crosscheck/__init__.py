"""Cross-check (issue 5)."""
