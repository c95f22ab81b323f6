"""The hull benchmarks' six body design variables (sensitivity_benchmark.py's, and
constraint_benchmark.py's memory baseline): the hull translated along x, y, z (metres per unit),
rotated about y and z (degrees per unit) and scaled along x (the scale factor's change per unit)."""


def add_body_variables(dvs, hull):
    dvs.addHandleDV('tx', hull, translate=[1, 0, 0], lower=-0.5, upper=0.5)
    dvs.addHandleDV('ty', hull, translate=[0, 1, 0], lower=-0.5, upper=0.5)
    dvs.addHandleDV('tz', hull, translate=[0, 0, 1], lower=-0.5, upper=0.5)
    dvs.addHandleDV('ry', hull, rotate=[0, 1, 0], lower=-5, upper=5)
    dvs.addHandleDV('rz', hull, rotate=[0, 0, 1], lower=-5, upper=5)
    dvs.addHandleDV('sx', hull, scale=[1, 0, 0], lower=-0.1, upper=0.1)
