/*
 * stripkit.h: the C API of stripkit (triangle strips), C99 and C++.
 *
 * Shaped like meshoptimizer's interface: plain arrays in and out, the caller owning
 * the memory wherever the result's size is known in advance. Every function checks
 * its pointers and sizes and never lets a panic cross into C: it returns a status
 * (functions returning int64_t: a count >= 0, or a negative stripkit_status), and
 * stripkit_last_error() gives the message of the thread's last failure. No function
 * keeps global state: calls on different threads run in parallel, and one stripkit_lod
 * handle may be read from several threads at once.
 *
 * Index conventions: a strip draws triangle i as (s[i], s[i+1], s[i+2]) for even i and
 * (s[i+1], s[i], s[i+2]) for odd i, so every triangle keeps its winding; a repeated
 * index draws nothing. Restart-separated buffers hold strips separated by a restart
 * index that is never a vertex id (0xFFFFFFFF, GL_PRIMITIVE_RESTART_FIXED_INDEX, by
 * default); stitched buffers are one strip joined by degenerate triangles.
 *
 * Build: cargo build -p stripkit-c --release (target/release/libstripkit.{so,a}), then
 * crates/stripkit-c/install.sh PREFIX; link with `pkg-config --libs stripkit` (shared),
 * `pkg-config --libs stripkit-static` (the archive and the system libraries it needs)
 * or CMake's find_package(stripkit). See docs/c-api.md.
 * Checked against the Rust side by crates/stripkit-c/tests/header.rs.
 */
#ifndef STRIPKIT_H
#define STRIPKIT_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Status codes: 0 success, negative an error (stripkit_last_error() says which). */
typedef enum stripkit_status {
    STRIPKIT_OK = 0,
    STRIPKIT_ERROR_NULL_POINTER = -1, /* a required pointer was null */
    STRIPKIT_ERROR_INVALID = -2,      /* bad input: index out of range, not whole triangles, level out of range */
    STRIPKIT_ERROR_BAD_OPTION = -3,   /* an option out of range, or options.size not this header's */
    STRIPKIT_ERROR_TOO_SMALL = -4,    /* the destination is smaller than the result */
    STRIPKIT_ERROR_FORMAT = -5,       /* a malformed .sets blob */
    STRIPKIT_ERROR_VERIFICATION = -6, /* the library's check of its own output failed (a bug) */
    STRIPKIT_ERROR_PANIC = -7,        /* the library panicked (a bug), caught at the boundary */
    STRIPKIT_ERROR_OTHER = -8
} stripkit_status;

/* stripkit_options.algorithm: the stripifier that runs (the CLI's --algorithm names). */
typedef enum stripkit_algorithm {
    STRIPKIT_ALGORITHM_AUTO = 0,        /* QSTRIP on quad-dominant meshes, greedy otherwise (default) */
    STRIPKIT_ALGORITHM_GREEDY = 1,      /* greedy lowest-degree strips with tunnelling */
    STRIPKIT_ALGORITHM_QSTRIP = 2,      /* quad sequences (triangle input: as greedy) */
    STRIPKIT_ALGORITHM_QUAD_SINGLE = 3, /* one strip per closed pure-quad component */
    STRIPKIT_ALGORITHM_CACHE = 4,       /* cache-aware short strips for a FIFO of cache_size */
    STRIPKIT_ALGORITHM_BALANCED = 5,    /* fewest indices with at most max_acmr FIFO misses per triangle */
    STRIPKIT_ALGORITHM_BATCH = 6,       /* strips planned for batch-shading GPUs (experimental) */
    STRIPKIT_ALGORITHM_SINGLE = 7       /* one strip per component; may add vertices: stripkit_stripify_mesh only */
} stripkit_algorithm;

/* stripkit_options.join: how strips are joined into one buffer. */
typedef enum stripkit_join {
    STRIPKIT_JOIN_RESTART = 0,   /* strips separated by the restart index (default) */
    STRIPKIT_JOIN_DEGENERATE = 1 /* one stitched strip; the restart index is unused */
} stripkit_join;

/*
 * Options of every stripping call. Initialise with stripkit_options_default(), then
 * change fields: `size` tells the library which version of the struct the caller was
 * built with (a mismatch is STRIPKIT_ERROR_BAD_OPTION, never a misread). A null
 * options pointer means the defaults.
 */
typedef struct stripkit_options {
    uint32_t size;          /* sizeof(stripkit_options), set by stripkit_options_default() */
    uint32_t algorithm;     /* a stripkit_algorithm; default STRIPKIT_ALGORITHM_AUTO */
    uint32_t cache_size;    /* FIFO entries for cache / balanced (and the ACMR figure); 1 to 65536, default 16 */
    uint32_t join;          /* a stripkit_join; default STRIPKIT_JOIN_RESTART */
    uint32_t restart_index; /* restart index of stripkit_stripify_mesh (the index-level calls take it as an argument); default 0xFFFFFFFF */
    uint32_t weld;          /* 1: weld bit-identical positions first (stripkit_stripify_mesh only); default 1 */
    double max_acmr;        /* bound of STRIPKIT_ALGORITHM_BALANCED, misses per triangle; default 0.8 */
} stripkit_options;

/* The default options, `size` set. */
stripkit_options stripkit_options_default(void);

/*
 * The message of this thread's last failed call, naming the function and what was
 * wrong; every function that returns a status clears it when it succeeds. Valid until
 * the thread's next stripkit call.
 */
const char* stripkit_last_error(void);

/*
 * The most indices stripkit_stripify (and stripkit_stripify16) writes for index_count
 * input indices, for any options: 7 per input triangle. O(1).
 */
size_t stripkit_stripify_bound(size_t index_count);

/*
 * Strips for a triangle list (meshoptimizer's meshopt_stripify with a destination size
 * and options). `indices` holds index_count / 3 triangles, every index below
 * vertex_count. Writes one buffer into destination (destination_size entries; use
 * stripkit_stripify_bound): strips separated by restart_index (STRIPKIT_JOIN_RESTART;
 * it must not be below vertex_count) or one stitched strip (STRIPKIT_JOIN_DEGENERATE).
 * Every output is verified to draw exactly the input triangles with their winding.
 * Returns the indices written, or a negative stripkit_status: null pointers, an empty
 * list or one that is not whole triangles, an index >= vertex_count, a too-small
 * destination, bad options, STRIPKIT_ALGORITHM_SINGLE (use stripkit_stripify_mesh).
 * options.restart_index and options.weld do not apply here. Cost: the algorithm's
 * (greedy: about linear in the triangles).
 */
int64_t stripkit_stripify(unsigned int* destination, size_t destination_size, const unsigned int* indices,
                          size_t index_count, size_t vertex_count, unsigned int restart_index,
                          const stripkit_options* options);

/* stripkit_stripify for 16-bit indices (vertex_count at most 65536; restart_index e.g. 0xFFFF). */
int64_t stripkit_stripify16(unsigned short* destination, size_t destination_size, const unsigned short* indices,
                            size_t index_count, size_t vertex_count, unsigned short restart_index,
                            const stripkit_options* options);

/* The most indices stripkit_unstripify writes for index_count strip indices: (index_count - 2) * 3. O(1). */
size_t stripkit_unstripify_bound(size_t index_count);

/*
 * The triangle list a strip buffer draws, three indices per triangle in strip order,
 * each with its winding; restart_index separates strips (pass an unused value such as
 * 0xFFFFFFFF for a stitched strip), degenerate triangles are dropped. Returns the
 * indices written into destination (destination_size entries; use
 * stripkit_unstripify_bound), or a negative stripkit_status. O(index_count).
 */
int64_t stripkit_unstripify(unsigned int* destination, size_t destination_size, const unsigned int* indices,
                            size_t index_count, unsigned int restart_index);

/* stripkit_unstripify for 16-bit indices. */
int64_t stripkit_unstripify16(unsigned short* destination, size_t destination_size, const unsigned short* indices,
                              size_t index_count, unsigned short restart_index);

/*
 * What stripkit_stripify_mesh gives: arrays owned by the library until
 * stripkit_mesh_result_free. Vertices added by STRIPKIT_ALGORITHM_SINGLE (edge splits)
 * follow the caller's: added vertex k has id vertex_count + k, position
 * added_positions[3k..3k+3] and is the midpoint of the edge added_from[2k], added_from[2k+1]
 * (either may itself be an added vertex of lower id), so the caller blends its own
 * attributes the same way. Other algorithms add none.
 */
typedef struct stripkit_mesh_result {
    const unsigned int* indices;  /* the strip buffer, joined as options.join says */
    size_t index_count;           /* entries in indices */
    size_t triangle_count;        /* triangles the strips draw */
    const float* added_positions; /* 3 floats per added vertex */
    const unsigned int* added_from; /* 2 vertex ids per added vertex */
    size_t added_count;           /* vertices added */
    void* internal;               /* the library's storage; do not touch */
} stripkit_mesh_result;

/*
 * Strips for a mesh: vertex_count positions (3 floats each) and index_count / 3
 * triangles, for every algorithm (STRIPKIT_ALGORITHM_SINGLE included). Positions steer
 * the algorithms that use them, and options.weld merges bit-identical positions first.
 * The strips use options.restart_index with STRIPKIT_JOIN_RESTART (it must not be a
 * vertex id). On success fills *result (free it with stripkit_mesh_result_free) and
 * returns STRIPKIT_OK; otherwise *result is emptied and a negative status returned
 * (null pointers, an index >= vertex_count, not whole triangles, bad options).
 */
int stripkit_stripify_mesh(const float* positions, size_t vertex_count, const unsigned int* indices,
                           size_t index_count, const stripkit_options* options, stripkit_mesh_result* result);

/* Frees the arrays of a stripkit_stripify_mesh result and empties it; null or an emptied result is a no-op. */
void stripkit_mesh_result_free(stripkit_mesh_result* result);

/* A multiresolution strip model (SETS) decoded from a .sets blob (`stripkit lod build` writes them). */
typedef struct stripkit_lod stripkit_lod;

/*
 * Decodes a .sets blob of `size` bytes (checksum, every count, range and level checked,
 * so that no extraction can go out of bounds) and sets *lod to a handle (free it with
 * stripkit_lod_free); the blob may be freed afterwards. Returns STRIPKIT_OK, or a
 * negative status (STRIPKIT_ERROR_FORMAT with the byte offset for a malformed blob;
 * *lod is then null). O(size).
 */
int stripkit_lod_open(const void* data, size_t size, stripkit_lod** lod);

/* Frees a handle of stripkit_lod_open; null is a no-op. */
void stripkit_lod_free(stripkit_lod* lod);

/* The coarsest level: levels run from 0 (the input mesh) to this. Negative: a status. */
int64_t stripkit_lod_levels(const stripkit_lod* lod);

/* Vertices any level may name (3 floats each in stripkit_lod_positions). Negative: a status. */
int64_t stripkit_lod_vertex_count(const stripkit_lod* lod);

/* Copies the positions (3 floats per vertex) into destination; returns the floats written or a negative status. */
int64_t stripkit_lod_positions(const stripkit_lod* lod, float* destination, size_t destination_size);

/* Triangles drawn at `level` (0 to stripkit_lod_levels; past it is STRIPKIT_ERROR_INVALID). */
int64_t stripkit_lod_triangles(const stripkit_lod* lod, unsigned int level);

/* The first level with at most max_triangles triangles (the coarsest when none has so few). */
int64_t stripkit_lod_level_for_triangles(const stripkit_lod* lod, uint64_t max_triangles);

/* Entries stripkit_lod_extract writes for `level` (strip indices plus one restart between strips). */
int64_t stripkit_lod_extract_bound(const stripkit_lod* lod, unsigned int level);

/*
 * The strips of `level`, non-empty ones separated by restart_index (not a vertex id),
 * into destination (destination_size entries; use stripkit_lod_extract_bound). Returns
 * the entries written or a negative status (level out of range, too-small destination).
 * Cost: about linear in the model's size (each strip's versions walked once).
 */
int64_t stripkit_lod_extract(const stripkit_lod* lod, unsigned int level, unsigned int* destination,
                             size_t destination_size, unsigned int restart_index);

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* STRIPKIT_H */
