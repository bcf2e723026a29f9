"""Experiments (thesis Ch. 6–7): free-vibration calibration, shake-table record preparation,
probabilistic validation of the model against tests, and the model ensemble to compare with.

Modules: :mod:`.free_vibration` (reading a measured tilt history, impacts and half-cycles),
:mod:`.calibrate` (p, λ, c_r from a free-vibration test, Sec 6.3.5/6.4.3), :mod:`.synthetic`
(an engine-made "measurement"), :mod:`.scale_model` (Eq 6.5 time scaling and table limits),
:mod:`.validate` (Ch. 7 statistics), :mod:`.validate_report` (figure and report) and
:mod:`.ensemble` (a project run over a stochastic ensemble).  :mod:`.run` holds the library functions of the
commands (``rd.calibration``, ``rd.validation``, ``rd.ensemble``).
"""
