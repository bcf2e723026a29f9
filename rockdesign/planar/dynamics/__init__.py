"""Equations of motion and the event-driven integrator (SPEC §3); see docs/engine.md."""
