"""The MPI processes of pvbatch --symmetric (every process runs the script on its piece of the
data), as the package needs them: how many there are, and reductions of numpy arrays over all of
them through VTK's global controller. Without MPI (pvpython, python3, one process) every
reduction is the identity."""
import numpy as np


def controller():
    """VTK's global multi-process controller when there are several processes, else None."""
    try:
        from vtkmodules.vtkParallelCore import vtkMultiProcessController
    except ImportError:
        return None
    c = vtkMultiProcessController.GetGlobalController()
    return c if c is not None and c.GetNumberOfProcesses() > 1 else None


def rank():
    c = controller()
    return c.GetLocalProcessId() if c is not None else 0


def all_reduce(values, operation):
    """values (a number or an array) reduced element-wise over the processes with operation 'max',
    'min' or 'sum'; the same result on every process (in the array's dtype: float64 or int64)."""
    array = np.atleast_1d(np.asarray(values))
    c = controller()
    if c is None:
        return array if np.ndim(values) else array[0]
    from vtkmodules.vtkParallelCore import vtkCommunicator
    from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
    integer = np.issubdtype(array.dtype, np.integer) or array.dtype == bool
    send = numpy_to_vtk(array.astype(np.int64 if integer else np.float64), deep=1)
    receive = send.NewInstance()   # the same VTK type, as AllReduce needs
    receive.SetNumberOfTuples(len(array))
    op = {'max': vtkCommunicator.MAX_OP, 'min': vtkCommunicator.MIN_OP, 'sum': vtkCommunicator.SUM_OP}[operation]
    c.AllReduce(send, receive, op)
    result = vtk_to_numpy(receive).copy()
    return result if np.ndim(values) else result[0]


def all_gather(values):
    """The 1D float64 arrays of every process concatenated in process order (the same on every
    process); values itself on one process."""
    array = np.ascontiguousarray(np.asarray(values, dtype=np.float64).reshape(-1))
    c = controller()
    if c is None:
        return array
    from vtkmodules.vtkCommonCore import vtkDoubleArray
    from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
    send = numpy_to_vtk(array, deep=1) if len(array) else vtkDoubleArray()
    receive = vtkDoubleArray()
    c.AllGatherV(send, receive)
    return vtk_to_numpy(receive).copy() if receive.GetNumberOfTuples() else np.zeros(0)
