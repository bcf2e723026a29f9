"""A small, quick podium project (two built-in records, rigid superstructure) for the library tests."""

SMALL_PODIUM = """\
[project]
name = "stocky podium"

[podium]
columns = 20
cap_beam_mass = "200 t"
height = "3.0 m"
width = "0.6 m"
mass = "2.7 t"
mass_distribution = 0.3333

[superstructure]
mass = "600 t"
period = "rigid"

[excitation]
records = ["p695-ff/12a", "p695-ff/15b"]
scale = { method = "pga", target = "0.1 g" }

[analysis]
overturn = "static"
overturn_probability_limit = 0.8   # two records: the one-sided 95 % bound with 0 overturns is 0.776
"""
