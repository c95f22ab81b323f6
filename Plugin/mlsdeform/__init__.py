"""MLS deformation for design optimization, in pvpython and pvbatch once the MLSDeform plugin is
loaded (``LoadPlugin(...)``, or ``paraview --plugins=MLSDeform``): ``import mlsdeform``; or in
Debian's python3 with the plugin's folder (where the package is copied) on sys.path, on a plain
VTK pipeline (``mlsdeform.vtkfoam``).

``DesignVariables`` puts design variables on the Handle regions of an MLS Deform filter and
gives the deformed points and their exact derivatives, with the interface of pyGeo's DVGeometry
(``addHandleDV``, ``setDesignVars``, ``update``, ``totalSensitivity``, ``totalSensitivityProd``,
``checkDerivatives``), for scipy.optimize, pyOptSparse or OpenMDAO. ``DesignConstraints`` adds
the constraint functions with their gradients (thickness, volume, area, linear, mesh quality) in
the form of pyGeo's DVConstraints. ``designOfExperiments`` turns
a Latin hypercube or a table of values into variants (OpenFOAM cases, or FEM decks read by the
Mesh File reader) with a mesh-quality verdict each (checkMesh's, or an FEM solver's).
``readFoamSensitivity`` turns an OpenFOAM adjoint sensitivity field into dJ/dX on the
deformation's points (for ``totalSensitivity``) and ``readFoamObjective`` reads J;
``readCalculixSensitivity`` and ``readCalculixObjective`` do the same for CalculiX's shape
sensitivities of a variant deck (``mlsdeform.meshfile`` reads decks and writes their variants).
"""
from .deformer import _load_wrapping
from .design import DesignVariables, KINDS
from .constraints import DesignConstraints
from .adjoint import readFoamDictionary, readFoamObjective, readFoamSensitivity
from .calculix import exactSensitivity, readCalculixObjective, readCalculixSensitivity
from .experiments import FEM_THRESHOLDS, THRESHOLDS, designOfExperiments, latinHypercube, meshQuality, passes, readTable

# The filters' Python wrapping, now: a VTK object handed to Python before it is loaded keeps its
# plain base class (and lacks the sensitivity methods).
_load_wrapping()

__all__ = ["DesignConstraints", "DesignVariables", "FEM_THRESHOLDS", "KINDS", "THRESHOLDS", "designOfExperiments", "latinHypercube", "meshQuality", "passes",
           "exactSensitivity", "readCalculixObjective", "readCalculixSensitivity", "readFoamDictionary", "readFoamObjective",
           "readFoamSensitivity", "readTable"]
