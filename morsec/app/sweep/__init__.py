"""`morsec sweep`: fleets of runs of one scene over seeds and parameters, on this machine or a Dask cluster.

spec (the sweep file) -> plan (variants, builds, runs; instrument adds the metrics' sensors; paths sets the
values) -> engine (local threads or Dask) -> execute (one run: `morsec run`, the client; metrics from its
streams) -> table (Parquet and CSV, --resume) -> summary (text, CSV, PNG); driver ties them together."""
