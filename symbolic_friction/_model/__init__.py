"""symbolic_friction._model"""
