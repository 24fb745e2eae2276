"""symbolic_friction._infra"""
