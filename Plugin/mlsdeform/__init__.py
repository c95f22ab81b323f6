"""MLS deformation for design optimization, in pvpython and pvbatch once the MLSDeform plugin is
loaded (``LoadPlugin(...)``, or ``paraview --plugins=MLSDeform``): ``import mlsdeform``.

``DesignVariables`` puts design variables on the Handle regions of an MLS Deform filter and
gives the deformed points and their exact derivatives, with the interface of pyGeo's DVGeometry
(``addHandleDV``, ``setDesignVars``, ``update``, ``totalSensitivity``,
``totalSensitivityProd``, ``checkDerivatives``), for scipy.optimize, pyOptSparse or OpenMDAO.
"""
from .design import DesignVariables, KINDS

__all__ = ["DesignVariables", "KINDS"]
