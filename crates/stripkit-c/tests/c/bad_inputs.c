/*
 * Bad inputs through stripkit's C API, built with -fsanitize=address,undefined by
 * scripts/test: null pointers, out-of-range indices and levels, too-small destinations,
 * wrong options and garbage .sets blobs must each give their status and a message,
 * never a crash, a write past the stated size or a leak.
 *
 *   bad_inputs [model.sets]    (a valid model adds the LoD checks on real data)
 *
 * Prints "c: N passed, F failed" and exits 1 on any failure.
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "stripkit.h"

static int passed = 0, failed = 0;

static void check(int ok, const char* what, long line) {
    if (ok) {
        ++passed;
    } else {
        ++failed;
        fprintf(stderr, "FAILED line %ld: %s (last error: %s)\n", line, what, stripkit_last_error());
    }
}
#define CHECK(cond) check((cond), #cond, __LINE__)
/* A failure with this status, and a message naming the function. */
#define FAILS(call, status, name) \
    check((call) == (status) && strstr(stripkit_last_error(), name) != NULL, #call, __LINE__)

/* A 2 x 2 quad grid: 9 vertices, 8 triangles. */
static const unsigned int grid[24] = {0, 3, 1, 1, 3, 4, 1, 4, 2, 2, 4, 5, 3, 6, 4, 4, 6, 7, 4, 7, 5, 5, 7, 8};
static const float grid_positions[27] = {0, 0, 0, 1, 0, 0, 2, 0, 0, 0, 1, 0, 1, 1, 0, 2, 1, 0, 0, 2, 0, 1, 2, 0, 2, 2, 0};

static void index_level(void) {
    unsigned int out[64 + 4];
    unsigned short grid16[24], out16[64];
    unsigned int bad[24];
    stripkit_options options = stripkit_options_default();
    int64_t n, k;
    size_t i;

    CHECK(options.size == sizeof(stripkit_options));
    CHECK(stripkit_stripify_bound(24) == 56);
    n = stripkit_stripify(out, 64, grid, 24, 9, 0xFFFFFFFFu, NULL);
    CHECK(n > 0 && n <= 56);
    CHECK(strcmp(stripkit_last_error(), "") == 0);
    k = stripkit_unstripify(out + n, 0, out, (size_t)n, 0xFFFFFFFFu); /* too small on purpose */
    CHECK(k == STRIPKIT_ERROR_TOO_SMALL);

    FAILS(stripkit_stripify(NULL, 64, grid, 24, 9, 0xFFFFFFFFu, NULL), STRIPKIT_ERROR_NULL_POINTER, "stripkit_stripify");
    FAILS(stripkit_stripify(out, 64, NULL, 24, 9, 0xFFFFFFFFu, NULL), STRIPKIT_ERROR_NULL_POINTER, "indices is null");
    FAILS(stripkit_stripify(out, 64, grid, 0, 9, 0xFFFFFFFFu, NULL), STRIPKIT_ERROR_INVALID, "empty");
    FAILS(stripkit_stripify(out, 64, grid, 23, 9, 0xFFFFFFFFu, NULL), STRIPKIT_ERROR_INVALID, "multiple of 3");
    FAILS(stripkit_stripify(out, 64, grid, 24, 8, 0xFFFFFFFFu, NULL), STRIPKIT_ERROR_INVALID, "vertex 8");
    memcpy(bad, grid, sizeof bad);
    bad[17] = 0xFFFFFFFFu;
    FAILS(stripkit_stripify(out, 64, bad, 24, 9, 0xFFFFFFFFu, NULL), STRIPKIT_ERROR_INVALID, "index 17");
    FAILS(stripkit_stripify(out, 64, grid, 24, 9, 4, NULL), STRIPKIT_ERROR_BAD_OPTION, "restart");

    /* Too small: nothing written past the size given (the canaries stay). */
    for (i = 0; i < 68; ++i) out[i] = 0xC0FFEEu;
    FAILS(stripkit_stripify(out, (size_t)n - 1, grid, 24, 9, 0xFFFFFFFFu, NULL), STRIPKIT_ERROR_TOO_SMALL, "destination");
    for (i = (size_t)n - 1; i < 68; ++i) CHECK(out[i] == 0xC0FFEEu);

    options.size = 8;
    FAILS(stripkit_stripify(out, 64, grid, 24, 9, 0xFFFFFFFFu, &options), STRIPKIT_ERROR_BAD_OPTION, "options.size");
    options = stripkit_options_default();
    options.algorithm = 99;
    FAILS(stripkit_stripify(out, 64, grid, 24, 9, 0xFFFFFFFFu, &options), STRIPKIT_ERROR_BAD_OPTION, "algorithm 99");
    options = stripkit_options_default();
    options.join = 2;
    FAILS(stripkit_stripify(out, 64, grid, 24, 9, 0xFFFFFFFFu, &options), STRIPKIT_ERROR_BAD_OPTION, "join 2");
    options = stripkit_options_default();
    options.cache_size = 0;
    FAILS(stripkit_stripify(out, 64, grid, 24, 9, 0xFFFFFFFFu, &options), STRIPKIT_ERROR_BAD_OPTION, "cache");
    options = stripkit_options_default();
    options.algorithm = STRIPKIT_ALGORITHM_BALANCED;
    options.max_acmr = -1.0;
    FAILS(stripkit_stripify(out, 64, grid, 24, 9, 0xFFFFFFFFu, &options), STRIPKIT_ERROR_BAD_OPTION, "stripkit_stripify");
    options = stripkit_options_default();
    options.algorithm = STRIPKIT_ALGORITHM_SINGLE;
    FAILS(stripkit_stripify(out, 64, grid, 24, 9, 0xFFFFFFFFu, &options), STRIPKIT_ERROR_INVALID, "single");
    options = stripkit_options_default();
    options.join = STRIPKIT_JOIN_DEGENERATE;
    n = stripkit_stripify(out, 64, grid, 24, 9, 0, &options); /* restart unused when stitched */
    CHECK(n > 0);
    CHECK(stripkit_unstripify(out + n, 64 - (size_t)n, out, (size_t)n, 0xFFFFFFFFu) == 24);

    for (i = 0; i < 24; ++i) grid16[i] = (unsigned short)grid[i];
    n = stripkit_stripify16(out16, 64, grid16, 24, 9, 0xFFFF, NULL);
    CHECK(n > 0);
    FAILS(stripkit_stripify16(out16, 64, grid16, 24, 70000, 0xFFFF, NULL), STRIPKIT_ERROR_INVALID, "16-bit");
    FAILS(stripkit_stripify16(out16, 2, grid16, 24, 9, 0xFFFF, NULL), STRIPKIT_ERROR_TOO_SMALL, "stripkit_stripify16");
    FAILS(stripkit_unstripify16(NULL, 64, out16, (size_t)n, 0xFFFF), STRIPKIT_ERROR_NULL_POINTER, "destination");
    CHECK(stripkit_unstripify16(out16 + n, 64 - (size_t)n, out16, (size_t)n, 0xFFFF) == 24);
    FAILS(stripkit_unstripify(out, 64, NULL, 3, 0xFFFFFFFFu), STRIPKIT_ERROR_NULL_POINTER, "stripkit_unstripify");
    CHECK(stripkit_unstripify_bound(0) == 0 && stripkit_unstripify_bound(5) == 9);
}

static void mesh_level(void) {
    stripkit_mesh_result result;
    stripkit_options options = stripkit_options_default();
    unsigned int bad[24];

    CHECK(stripkit_stripify_mesh(grid_positions, 9, grid, 24, NULL, &result) == STRIPKIT_OK);
    CHECK(result.triangle_count == 8 && result.index_count > 0 && result.added_count == 0);
    stripkit_mesh_result_free(&result);
    CHECK(result.indices == NULL && result.internal == NULL);
    stripkit_mesh_result_free(&result); /* twice: a no-op */
    stripkit_mesh_result_free(NULL);

    options.algorithm = STRIPKIT_ALGORITHM_SINGLE;
    CHECK(stripkit_stripify_mesh(grid_positions, 9, grid, 24, &options, &result) == STRIPKIT_OK);
    CHECK(result.triangle_count >= 8);
    stripkit_mesh_result_free(&result);

    FAILS(stripkit_stripify_mesh(grid_positions, 9, grid, 24, NULL, NULL), STRIPKIT_ERROR_NULL_POINTER, "result");
    FAILS(stripkit_stripify_mesh(NULL, 9, grid, 24, NULL, &result), STRIPKIT_ERROR_NULL_POINTER, "positions");
    CHECK(result.indices == NULL && result.internal == NULL);
    FAILS(stripkit_stripify_mesh(grid_positions, 9, NULL, 24, NULL, &result), STRIPKIT_ERROR_NULL_POINTER, "indices");
    FAILS(stripkit_stripify_mesh(grid_positions, 9, grid, 22, NULL, &result), STRIPKIT_ERROR_INVALID, "multiple of 3");
    memcpy(bad, grid, sizeof bad);
    bad[5] = 9;
    FAILS(stripkit_stripify_mesh(grid_positions, 9, bad, 24, NULL, &result), STRIPKIT_ERROR_INVALID, "vertex 9");
    FAILS(stripkit_stripify_mesh(grid_positions, (size_t)-1, grid, 24, NULL, &result), STRIPKIT_ERROR_INVALID, "memory");
    options = stripkit_options_default();
    options.restart_index = 3;
    FAILS(stripkit_stripify_mesh(grid_positions, 9, grid, 24, &options, &result), STRIPKIT_ERROR_BAD_OPTION, "restart");
}

static void garbage_blobs(void) {
    unsigned char blob[256];
    stripkit_lod* lod = (stripkit_lod*)&blob; /* must be reset to null on failure */
    size_t i;
    for (i = 0; i < sizeof blob; ++i) blob[i] = (unsigned char)(i * 37 + 11);
    FAILS(stripkit_lod_open(blob, sizeof blob, &lod), STRIPKIT_ERROR_FORMAT, "stripkit_lod_open");
    CHECK(lod == NULL);
    memcpy(blob, "SKLODSET", 8);
    FAILS(stripkit_lod_open(blob, sizeof blob, &lod), STRIPKIT_ERROR_FORMAT, "byte");
    FAILS(stripkit_lod_open(blob, 3, &lod), STRIPKIT_ERROR_FORMAT, "stripkit_lod_open");
    FAILS(stripkit_lod_open(NULL, 10, &lod), STRIPKIT_ERROR_NULL_POINTER, "data");
    FAILS(stripkit_lod_open(blob, 10, NULL), STRIPKIT_ERROR_NULL_POINTER, "lod");
    FAILS(stripkit_lod_levels(NULL), STRIPKIT_ERROR_NULL_POINTER, "stripkit_lod_levels");
    FAILS(stripkit_lod_vertex_count(NULL), STRIPKIT_ERROR_NULL_POINTER, "stripkit_lod_vertex_count");
    FAILS(stripkit_lod_extract(NULL, 0, NULL, 0, 0xFFFFFFFFu), STRIPKIT_ERROR_NULL_POINTER, "stripkit_lod_extract");
    stripkit_lod_free(NULL);
}

/* A real model: every level's strips draw the triangles the model gives; bad calls fail. */
static void model(const char* path) {
    FILE* file = fopen(path, "rb");
    unsigned char* data;
    long size, cut;
    stripkit_lod* lod = NULL;
    int64_t levels, level, bound, n, vertices;
    unsigned int* strips;
    unsigned int* tris;
    float* positions;

    CHECK(file != NULL);
    if (!file) return;
    fseek(file, 0, SEEK_END);
    size = ftell(file);
    rewind(file);
    data = malloc((size_t)size);
    CHECK(fread(data, 1, (size_t)size, file) == (size_t)size);
    fclose(file);

    /* Every truncation and a flipped byte in each region: a format error, never a crash. */
    for (cut = 0; cut < size; cut += 1 + cut / 8) FAILS(stripkit_lod_open(data, (size_t)cut, &lod), STRIPKIT_ERROR_FORMAT, "byte");
    for (cut = 0; cut < size; cut += 1 + size / 64) {
        data[cut] ^= 0x5A;
        FAILS(stripkit_lod_open(data, (size_t)size, &lod), STRIPKIT_ERROR_FORMAT, "stripkit_lod_open");
        data[cut] ^= 0x5A;
    }

    CHECK(stripkit_lod_open(data, (size_t)size, &lod) == STRIPKIT_OK);
    free(data);
    if (!lod) return;
    levels = stripkit_lod_levels(lod);
    vertices = stripkit_lod_vertex_count(lod);
    CHECK(levels > 0 && vertices > 0);
    positions = malloc(sizeof(float) * 3 * (size_t)vertices);
    CHECK(stripkit_lod_positions(lod, positions, 3 * (size_t)vertices) == 3 * vertices);
    FAILS(stripkit_lod_positions(lod, positions, 3 * (size_t)vertices - 1), STRIPKIT_ERROR_TOO_SMALL, "destination");
    free(positions);
    for (level = 0; level <= levels; level += 1 + levels / 7) {
        bound = stripkit_lod_extract_bound(lod, (unsigned int)level);
        strips = malloc(sizeof(unsigned int) * (size_t)bound);
        tris = malloc(sizeof(unsigned int) * (stripkit_unstripify_bound((size_t)bound) + 1));
        n = stripkit_lod_extract(lod, (unsigned int)level, strips, (size_t)bound, 0xFFFFFFFFu);
        CHECK(n == bound);
        CHECK(stripkit_unstripify(tris, stripkit_unstripify_bound((size_t)n), strips, (size_t)n, 0xFFFFFFFFu) ==
              3 * stripkit_lod_triangles(lod, (unsigned int)level));
        if (bound > 0)
            FAILS(stripkit_lod_extract(lod, (unsigned int)level, strips, (size_t)bound - 1, 0xFFFFFFFFu),
                  STRIPKIT_ERROR_TOO_SMALL, "destination");
        FAILS(stripkit_lod_extract(lod, (unsigned int)level, strips, (size_t)bound, 0), STRIPKIT_ERROR_BAD_OPTION, "restart");
        free(strips);
        free(tris);
    }
    CHECK(stripkit_lod_level_for_triangles(lod, 0) == levels);
    CHECK(stripkit_lod_level_for_triangles(lod, (uint64_t)-1) == 0);
    FAILS(stripkit_lod_extract_bound(lod, (unsigned int)levels + 1), STRIPKIT_ERROR_INVALID, "out of range");
    FAILS(stripkit_lod_triangles(lod, (unsigned int)levels + 1), STRIPKIT_ERROR_INVALID, "out of range");
    stripkit_lod_free(lod);
}

int main(int argc, char** argv) {
    index_level();
    mesh_level();
    garbage_blobs();
    if (argc > 1) model(argv[1]);
    printf("c: %d passed, %d failed\n", passed, failed);
    return failed == 0 ? 0 : 1;
}
