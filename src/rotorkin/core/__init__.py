"""rotorkin.core"""
