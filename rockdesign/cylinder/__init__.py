"""The free-standing solid cylinder that rocks and wobbles in 3D under bidirectional ground motion
(thesis Ch. 5): project section (:mod:`.project`), system (:mod:`.system`), closed-form quantities
(:mod:`.quantities`), equations of motion (:mod:`.eom`), integrator (:mod:`.kernel`, :mod:`.engine`),
commands (:mod:`.commands`, :mod:`.cli`), spectra (:mod:`.spectrum`).  See ``docs/cylinder.md``.
"""
