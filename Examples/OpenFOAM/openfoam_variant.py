"""The examples' and benchmarks' name for mlsdeform.foam (open_case, patch_region, layer_region,
morph, save_variant), which ships with the plugin: load the plugin before importing this."""
from mlsdeform.foam import layer_region, morph, open_case, patch_region, save_variant  # noqa: F401
