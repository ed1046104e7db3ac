"""The application: path -> build -> run, convert, scaffolding, docs and gallery, the test harness."""
