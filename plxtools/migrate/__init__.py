"""`plx migrate`: moving models between OpenPLX versions. For now only `--explain FROM TO`."""
