//! Figures of METRICS.md: strip counts, index counts per join, swaps, vertex-cache
//! miss ratios (FIFO, optionally LRU).
//! (Filled in by the strip-core work.)
