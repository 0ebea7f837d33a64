"""The same physics in Exudyn (PyPI ``exudyn``, C++ multibody, generalized-alpha at a fixed
step): the peer a user would pick today (issue 5). Optional: ``available()`` is False without
the package, and the report then leaves Exudyn's lines out.

- ``pendulum``: a 1 kg point mass on a SpringDamper to ground (rest length 1 m, stiffness k,
  damping c) under gravity 9.81, released horizontally at rest: pysolver's bilateral
  Force_Penalty DM - 1 with penalty k and penalty1 c (a SpringDamper acts along the line
  with the rate of its length, which is that penalty's force).
- ``oscillator``: the exact damped oscillator of tests/test_oscillator.py as a coordinate
  spring-damper on the vertical coordinate.
Both return (times, positions (n x 2), best wall time over `repeat` solves in seconds).
"""
import time

import numpy as np


def available():
    try:
        import exudyn  # noqa: F401
    except ImportError:
        return False
    return True


def _solve(mbs, sensor, h, end, out_dt, rho, repeat):
    import exudyn as exu
    settings = exu.SimulationSettings()
    settings.timeIntegration.numberOfSteps = int(round(end / h))
    settings.timeIntegration.endTime = end
    settings.timeIntegration.generalizedAlpha.spectralRadius = rho
    settings.timeIntegration.verboseMode = 0
    settings.displayComputationTime = False
    settings.displayStatistics = False
    settings.solutionSettings.writeSolutionToFile = False
    settings.solutionSettings.sensorsWritePeriod = out_dt
    best = np.inf
    for _ in range(repeat):
        t0 = time.perf_counter()
        exu.SolveDynamic(mbs, settings)
        best = min(best, time.perf_counter() - t0)
    data = mbs.GetSensorStoredData(sensor)
    return data[:, 0], data[:, 1:3], best


def pendulum(k, c, h, end=10.0, rho=0.8, repeat=3):
    """Penalty pendulum at fixed step h with spectral radius rho (Exudyn's default 0.8)."""
    import exudyn as exu
    import exudyn.itemInterface as ei
    sc = exu.SystemContainer()
    mbs = sc.AddSystem()
    ground = mbs.AddNode(ei.NodePointGround(referenceCoordinates=[0, 0, 0]))
    node = mbs.AddNode(ei.NodePoint2D(referenceCoordinates=[1, 0], initialCoordinates=[0, 0],
                                      initialVelocities=[0, 0]))
    mbs.AddObject(ei.MassPoint2D(physicsMass=1.0, nodeNumber=node))
    m_y = mbs.AddMarker(ei.MarkerNodeCoordinate(nodeNumber=node, coordinate=1))
    mbs.AddLoad(ei.LoadCoordinate(markerNumber=m_y, load=-9.81))
    m0 = mbs.AddMarker(ei.MarkerNodePosition(nodeNumber=ground))
    m1 = mbs.AddMarker(ei.MarkerNodePosition(nodeNumber=node))
    mbs.AddObject(ei.SpringDamper(markerNumbers=[m0, m1], referenceLength=1.0, stiffness=k,
                                  damping=c))
    sensor = mbs.AddSensor(ei.SensorNode(nodeNumber=node, storeInternal=True,
                                         outputVariableType=exu.OutputVariableType.Position))
    mbs.Assemble()
    return _solve(mbs, sensor, h, end, 0.01, rho, repeat)


def oscillator(h, m, k, c, g, z0, v0, end=3.0, rho=0.8, repeat=3):
    """Point mass on a vertical spring-damper (rest at z = 1) under gravity, fixed step h;
    positions column 1 is z."""
    import exudyn as exu
    import exudyn.itemInterface as ei
    sc = exu.SystemContainer()
    mbs = sc.AddSystem()
    ground = mbs.AddNode(ei.NodePointGround(referenceCoordinates=[0, 0, 0]))
    node = mbs.AddNode(ei.NodePoint2D(referenceCoordinates=[0, 1], initialCoordinates=[0, z0 - 1],
                                      initialVelocities=[0, v0]))
    mbs.AddObject(ei.MassPoint2D(physicsMass=m, nodeNumber=node))
    m_y = mbs.AddMarker(ei.MarkerNodeCoordinate(nodeNumber=node, coordinate=1))
    m_g = mbs.AddMarker(ei.MarkerNodeCoordinate(nodeNumber=ground, coordinate=1))
    mbs.AddLoad(ei.LoadCoordinate(markerNumber=m_y, load=-m * g))
    mbs.AddObject(ei.CoordinateSpringDamper(markerNumbers=[m_g, m_y], stiffness=k, damping=c))
    sensor = mbs.AddSensor(ei.SensorNode(nodeNumber=node, storeInternal=True,
                                         outputVariableType=exu.OutputVariableType.Position))
    mbs.Assemble()
    return _solve(mbs, sensor, h, end, 0.01, rho, repeat)
