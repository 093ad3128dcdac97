"""closurelab's Python helpers: `closurelab.tables` reads results tables into pandas and numpy."""
