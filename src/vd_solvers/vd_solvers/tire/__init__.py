"""Tire models: Magic Formula from .tir files and the thesis simple tire."""
