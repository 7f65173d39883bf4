#pragma once
// Loops over the rows of a slab (or over rays) that run on every core where
// the compiler has OpenMP, and one after the other where it has not. Used
// only where each iteration writes its own slots, and where the mesh grows,
// a row's share is counted first and its place fixed by the rows before it:
// the output is the same, vertex for vertex, on any number of threads.

#ifdef _OPENMP
#define STRATA_PRAGMA(text) _Pragma(#text)
#define STRATA_FOR_ROWS STRATA_PRAGMA(omp parallel for schedule(static))
#define STRATA_FOR_ROWS_SUM(...) STRATA_PRAGMA(omp parallel for schedule(static) reduction(+ : __VA_ARGS__))
// Pieces of uneven work (the flat regions' slabs), handed out as threads free up.
#define STRATA_FOR_PIECES_SUM(...) STRATA_PRAGMA(omp parallel for schedule(dynamic) reduction(+ : __VA_ARGS__))
#else
#define STRATA_FOR_ROWS
#define STRATA_FOR_ROWS_SUM(...)
#define STRATA_FOR_PIECES_SUM(...)
#endif
