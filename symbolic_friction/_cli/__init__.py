"""symbolic_friction._cli"""
