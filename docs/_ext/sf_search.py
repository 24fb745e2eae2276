"""The search index's English stemmer with each word's stem kept across pages, not only within one.

Sphinx stems every word of every page for the search index (``searchindex.js``) with snowballstemmer's
English stemmer, in pure Python when PyStemmer is not installed; it remembers the stems within one page
only, so the words every page shares (about 19,000 stemmings over this site's 39 pages) are stemmed again on
each: 1.0 of the build's 14 CPU-seconds, 0.3 once each word is stemmed once (measured).  A stem is a function
of the word alone (the stemmer keeps no state between words), so this extension keeps each one for the
build: the index is byte for byte what Sphinx alone writes.  Where Sphinx's English search language no longer
has the ``stem`` this wraps, it is left as it is (slower, the same index).
"""

from __future__ import annotations

from typing import Any

__all__ = ["setup"]


def _remembering(stem):
    """``stem(self, word)`` with each word's result kept on the search language object (one per build)."""

    def remembered(self: Any, word: str) -> str:
        known = self.__dict__.setdefault("_sf_stems", {})
        try:
            return known[word]
        except KeyError:
            known[word] = found = stem(self, word)
            return found

    remembered.__wrapped__ = stem  # type: ignore[attr-defined]
    return remembered


def setup(app):
    try:
        from sphinx.search.en import SearchEnglish
    except ImportError:
        SearchEnglish = None
    stem = getattr(SearchEnglish, "stem", None)
    if callable(stem) and not hasattr(stem, "__wrapped__"):
        SearchEnglish.stem = _remembering(stem)
    return {"version": "1", "parallel_read_safe": True, "parallel_write_safe": True}
