"""Solver mesh files (Abaqus/CalculiX decks) on a plain VTK pipeline: the plugin's Mesh File reader
and variant writer, for the design of experiments and for scripts without ParaView's server
manager (python3 with the plugin's folder on sys.path, or pvpython).

    reader = open_mesh('plate/plate.inp')
    deform = vtkfoam.morph(reader, 'hole1', (0.2, 0, 0), fixed=['fixed'])   # sets by name
    save_variant(deform, 'variant/plate.inp')
"""
import os

from .deformer import _load_wrapping


def source_of(algorithm):
    """The solver's mesh file an (updated) algorithm's output came from, as the variant writer
    finds it (the Mesh File reader's SourceFile field data, or the file of ParaView's CGNS, IOSS
    or Exodus II reader up the pipeline), and whether its variants get an FEM solver's verdict:
    ('', False) when none."""
    writer = _load_wrapping(readers=True).vtkMeshVariantWriter()
    writer.SetInputConnection(algorithm.GetOutputPort())
    return writer.FindSourceFile(), bool(writer.FindSourceIsFem())


def open_mesh(path):
    """The mesh file read (nodes, elements, every set as a 0/1 array), updated. Raises ValueError
    with the reader's message (file and line) when it cannot be read."""
    if os.path.isdir(path):
        raise ValueError(f"{path} is a folder: name the mesh file in it (e.g. its .inp deck)")
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
