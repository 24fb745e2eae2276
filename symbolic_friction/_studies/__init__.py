"""symbolic_friction._studies"""
