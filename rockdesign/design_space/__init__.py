"""Design exploration (SPEC §15, CONTRACT §6.3): the check over a grid of one or two project keys.

:mod:`.variants` parses ``--vary`` and builds each variant's project; :mod:`.grid` checks every variant
with the work they share done once and stops a variant once its verdict is decided; :mod:`.run` is
``rockdesign design`` (files: report/design_results.py, charts: report/design_figures.py, report:
report/design_report.py)."""
