"""How lkspace runs: where shards execute, worker processes and signals, progress on stderr."""
