"""Strong scaling of MLS Deform over MPI ranks (issue 14 point 6), run by
run-distributed-benchmark.sh: a tetrahedral box of SIZE^3 points (ParaView's Wavelet source,
which every rank makes its own piece of, tetrahedralized), a Handle block in the middle moved by
new translations, the box's sides Fixed. Prints one JSON line: points, samples, set-up (the
first update: sampling, Phi at the points, regions, factorization), the median wall time of a
variation (a new handle translation) and the bytes the ranks exchange per variation.
Usage: mpiexec -n N pvbatch distributed_scaling.py PLUGIN SIZE VARIATIONS"""
import json
import statistics
import sys
import time

import paraview.simple as pvs
from paraview import servermanager

plugin, size, variations = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
pvs.LoadPlugin(plugin, remote=False, ns=globals())
half = (size - 1) // 2
wavelet = pvs.Wavelet(WholeExtent=[-half, size - 1 - half] * 3)
tets = pvs.Tetrahedralize(Input=wavelet)
tets.UpdatePipeline()
handle = ConstraintRegion(Input=tets, Role='Handle')
handle.Region = 'Box'
handle.Region.UseReferenceBounds = 0
handle.Region.Position = [-0.2 * half] * 3
handle.Region.Length = [0.4 * half] * 3
fixed = ConstraintRegion(Input=tets, Role='Fixed', InsideOut=1)
fixed.Region = 'Box'
fixed.Region.UseReferenceBounds = 0
fixed.Region.Position = [-half + 0.5] * 3
fixed.Region.Length = [2 * half - 1.0] * 3
deform = MLSDeform(Input=tets, Regions=[handle, fixed], MeshQuality=0)
start = time.perf_counter()
deform.UpdatePipeline()
setup = time.perf_counter() - start
times = []
for v in range(variations):
    handle.Translation = [0.02 * half * (v + 1), 0, 0.01 * half]
    start = time.perf_counter()
    deform.UpdatePipeline()
    times.append(time.perf_counter() - start)
# figures from the data information (fetching the output would copy the mesh to rank 0)
info = deform.GetDataInformation()
value = lambda name: deform.FieldData[name].GetRange(0)[1] if name in deform.FieldData.keys() else None
ranks = servermanager.ActiveConnection.GetNumberOfDataPartitions()
handle_points = handle.GetDataInformation().GetNumberOfPoints()
print(json.dumps({
    'ranks': ranks, 'points_in_pieces': info.GetNumberOfPoints(), 'grid_points': size ** 3,
    'samples': value('NumberOfSamples'), 'integration_points': value('NumberOfIntegrationPoints'),
    'setup_s': round(setup, 3), 'filter_setup_s': value('SetupTime'),
    'variation_median_s': round(statistics.median(times), 4), 'variations_s': [round(t, 4) for t in times],
    # every rank receives each Dirichlet region's prescribed displacements (3 doubles per position)
    'handle_positions': handle_points, 'bytes_received_per_rank_per_variation': 24 * handle_points,
    'handle_residual': value('HandleResidual')}), flush=True)
