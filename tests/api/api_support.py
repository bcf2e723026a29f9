"""A small, quick podium project (two built-in records, rigid superstructure) for the library tests."""
from support import stocky_podium_toml

SMALL_PODIUM = stocky_podium_toml()
