"""The examples' and benchmarks' name for mlsdeform.foam (open_case, patch_region, layer_region,
morph, save_variant), which ships with the plugin: load the plugin before importing this; and
checkmesh, OpenFOAM's verdict on a case for the examples and tests."""
from mlsdeform.foam import layer_region, morph, open_case, patch_region, save_variant  # noqa: F401


def checkmesh(case):
    """checkMesh's verdict on a case folder (Debian's OpenFOAM environment): (ok, its log's text)."""
    import subprocess
    process = subprocess.run(['bash', '-c', 'source /usr/share/openfoam/etc/bashrc > /dev/null 2>&1; checkMesh -case "%s"'
                              % case], capture_output=True, text=True)
    return 'Mesh OK.' in process.stdout and process.returncode == 0, process.stdout
