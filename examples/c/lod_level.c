/*
 * lod_level: one level of detail from a .sets model through stripkit's C API.
 *
 *   lod_level model.sets LEVEL
 *
 * Reads the file into memory, opens it (stripkit_lod_open), extracts the strips of
 * LEVEL separated by 0xFFFFFFFF and prints one index per line; the level, its
 * triangles and the vertex count go to stderr.
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "stripkit.h"

int main(int argc, char** argv) {
    FILE* file;
    long size;
    void* data;
    stripkit_lod* lod = NULL;
    unsigned int* strips;
    int64_t level, bound, written, i;

    if (argc != 3) {
        fprintf(stderr, "usage: %s model.sets LEVEL\n", argv[0]);
        return 2;
    }
    file = fopen(argv[1], "rb");
    if (!file || fseek(file, 0, SEEK_END) != 0 || (size = ftell(file)) < 0) {
        fprintf(stderr, "cannot read %s\n", argv[1]);
        return 2;
    }
    rewind(file);
    data = malloc((size_t)size + 1);
    if (fread(data, 1, (size_t)size, file) != (size_t)size) {
        fprintf(stderr, "cannot read %s\n", argv[1]);
        return 2;
    }
    fclose(file);

    if (stripkit_lod_open(data, (size_t)size, &lod) != STRIPKIT_OK) {
        fprintf(stderr, "%s\n", stripkit_last_error());
        return 1;
    }
    free(data); /* the handle keeps what it needs */
    level = atoll(argv[2]);
    if (level > stripkit_lod_levels(lod)) level = stripkit_lod_levels(lod);
    bound = stripkit_lod_extract_bound(lod, (unsigned int)level);
    if (bound < 0) {
        fprintf(stderr, "%s\n", stripkit_last_error());
        return 1;
    }
    strips = malloc(sizeof(unsigned int) * (size_t)(bound + 1));
    written = stripkit_lod_extract(lod, (unsigned int)level, strips, (size_t)bound, 0xFFFFFFFFu);
    if (written < 0) {
        fprintf(stderr, "%s\n", stripkit_last_error());
        return 1;
    }
    for (i = 0; i < written; ++i) printf("%u\n", strips[i]);
    fprintf(stderr, "level %lld of %lld: %lld triangles, %lld vertices, %lld indices\n", (long long)level,
            (long long)stripkit_lod_levels(lod), (long long)stripkit_lod_triangles(lod, (unsigned int)level),
            (long long)stripkit_lod_vertex_count(lod), (long long)written);
    free(strips);
    stripkit_lod_free(lod);
    return 0;
}
