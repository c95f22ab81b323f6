"""Solver mesh files (Abaqus/CalculiX decks) on a plain VTK pipeline: the plugin's Mesh File reader
and variant writer, for the design of experiments and for scripts without ParaView's server
manager (python3 with the plugin's folder on sys.path, or pvpython).

    reader = open_mesh('plate/plate.inp')
    deform = vtkfoam.morph(reader, 'hole1', (0.2, 0, 0), fixed=['fixed'])   # sets by name
    save_variant(deform, 'variant/plate.inp')
"""
import os

from .deformer import _load_wrapping


def source_file(data):
    """The mesh file a dataset was read from (the Mesh File reader's SourceFile field data), or ''."""
    path = data.GetFieldData().GetAbstractArray('SourceFile') if data is not None else None
    return path.GetValue(0) if path is not None and path.GetNumberOfValues() else ''


def fem_verdict(data):
    """Whether a dataset came from a structural solver's mesh file, whose variants get an FEM
    solver's verdict (the Mesh File reader's QualityVerdict field data "FemSolver")."""
    verdict = data.GetFieldData().GetAbstractArray('QualityVerdict') if data is not None else None
    return verdict is not None and verdict.GetNumberOfValues() > 0 and verdict.GetValue(0) == 'FemSolver'


def open_mesh(path):
    """The mesh file read (nodes, elements, every set as a 0/1 array), updated. Raises ValueError
    with the reader's message (file and line) when it cannot be read."""
    if not os.path.isfile(path):
        raise ValueError(f"the mesh file {path} does not exist")
    reader = _load_wrapping(readers=True).vtkMeshFileReader()
    reader.SetFileName(path)
    reader.Update()
    if reader.GetErrorCode() != 0 or reader.GetOutput().GetNumberOfPoints() == 0:
        raise ValueError(reader.GetLastError() or f"{path} holds no nodes")
    return reader


def save_variant(deform, path, overwrite=False):
    """Writes the variant of the deformation's source mesh file to path (the deck and its includes
    beside it, only the node coordinates changed); raises RuntimeError with the reason if nothing
    was written."""
    writer = _load_wrapping(readers=True).vtkMeshVariantWriter()
    writer.SetInputConnection(deform.GetOutputPort())
    writer.SetFileName(path)
    writer.SetOverwrite(1 if overwrite else 0)
    writer.Write()
    if writer.GetErrorCode() != 0 or not os.path.exists(path):
        raise RuntimeError(writer.GetLastError() or f"the variant {path} was not written")
