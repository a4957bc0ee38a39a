"""The orthographic Section 2 rows: a rigid body under a motion model (see ``rigid/model.py``)."""
