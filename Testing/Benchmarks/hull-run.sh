# Sourced by the hull benchmarks (run-sensitivity-benchmark.sh, run-constraint-benchmark.sh) once
# their arguments are read: with root, here, size and name set, it sets build, plugin, work (the
# folder of the cached cases, shared by the benchmarks), case (the hull case of that size, built
# once by openfoam/make-hull-case.sh and cached), run (a fresh folder work/name-size), built (when
# the plugin was built) and plugin_path, after copying the plugin's folder (with the mlsdeform
# package's wrapping beside it) into run/plugin, so that a rebuild during the runs does not mix
# builds: its libraries are found first through LD_LIBRARY_PATH=$plugin_path.
build=${MLSDEFORM_BUILD:-$root/build}
plugin=${MLSDEFORM_PLUGIN:-$build/lib/paraview-5.11/plugins/MLSDeform/MLSDeform.so}
work=${MLSDEFORM_BENCHMARK_DIR:-$build/openfoam-benchmark}
[ -f "$plugin" ] || bash "$root/Testing/setup.sh"
command -v snappyHexMesh > /dev/null || [ -x /usr/bin/snappyHexMesh ] || bash "$root/Testing/setup.sh"
mkdir -p "$work"
work=$(cd "$work" && pwd)
case=$(bash "$here/cached-hull-case.sh" "$size" "$work")
run=$work/$name-$size
rm -rf "$run"
mkdir -p "$run"
built=$(date -r "$plugin" '+%F %T')
cp -r "$(dirname "$plugin")" "$run/plugin"
plugin_path=$run/plugin${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
