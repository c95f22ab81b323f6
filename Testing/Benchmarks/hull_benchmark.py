"""What the hull benchmarks (sensitivity_benchmark.py, constraint_benchmark.py) share: the six body
design variables (the hull translated along x, y, z in metres per unit, rotated about y and z in
degrees per unit, scaled along x by the scale factor's change per unit) and a call's timing."""
import time


def add_body_variables(dvs, hull):
    dvs.addHandleDV('tx', hull, translate=[1, 0, 0], lower=-0.5, upper=0.5)
    dvs.addHandleDV('ty', hull, translate=[0, 1, 0], lower=-0.5, upper=0.5)
    dvs.addHandleDV('tz', hull, translate=[0, 0, 1], lower=-0.5, upper=0.5)
    dvs.addHandleDV('ry', hull, rotate=[0, 1, 0], lower=-5, upper=5)
    dvs.addHandleDV('rz', hull, rotate=[0, 0, 1], lower=-5, upper=5)
    dvs.addHandleDV('sx', hull, scale=[1, 0, 0], lower=-0.1, upper=0.1)


def timed(function):
    """(seconds, result) of function()."""
    start = time.perf_counter()
    result = function()
    return time.perf_counter() - start, result
