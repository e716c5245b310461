/*
 * strip_obj: strips an OBJ mesh through stripkit's C API and prints the strip buffer.
 *
 *   strip_obj [--mesh] [--algorithm N] [--join N] [--time RUNS] mesh.obj
 *
 * Reads the `v` and `f` lines (faces fanned from their first corner), calls
 * stripkit_stripify on the triangle list (or stripkit_stripify_mesh with the positions
 * under --mesh, which `single` needs), checks with stripkit_unstripify that the strips
 * draw every triangle, and prints one index per line, then for each vertex the
 * algorithm added "added X Y Z A B" (position bits in hex, the edge it splits).
 * --time RUNS prints the median CPU time of the stripify call instead, in milliseconds.
 */
#define _POSIX_C_SOURCE 199309L /* clock_gettime under -std=c99 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "stripkit.h"

typedef struct {
    float* positions;
    size_t vertex_count, vertex_capacity;
    unsigned int* indices;
    size_t index_count, index_capacity;
} obj_mesh;

static void* grow(void* data, size_t* capacity, size_t needed, size_t item) {
    if (needed <= *capacity) return data;
    *capacity = needed * 2;
    data = realloc(data, *capacity * item);
    if (!data) {
        fprintf(stderr, "out of memory\n");
        exit(1);
    }
    return data;
}

/* The OBJ's positions and fanned faces; 0 on failure. */
static int read_obj(const char* path, obj_mesh* mesh) {
    FILE* file = fopen(path, "r");
    char line[4096];
    if (!file) {
        fprintf(stderr, "cannot open %s\n", path);
        return 0;
    }
    memset(mesh, 0, sizeof *mesh);
    while (fgets(line, sizeof line, file)) {
        if (line[0] == 'v' && line[1] == ' ') {
            float* p;
            mesh->positions = grow(mesh->positions, &mesh->vertex_capacity, 3 * (mesh->vertex_count + 1), sizeof(float));
            p = mesh->positions + 3 * mesh->vertex_count++;
            if (sscanf(line + 2, "%f %f %f", &p[0], &p[1], &p[2]) != 3) {
                fprintf(stderr, "%s: bad vertex line: %s", path, line);
                fclose(file);
                return 0;
            }
        } else if (line[0] == 'f' && line[1] == ' ') {
            unsigned int corners[256];
            size_t n = 0, i;
            char* token = strtok(line + 2, " \t\r\n");
            for (; token && n < 256; token = strtok(NULL, " \t\r\n")) {
                long v = strtol(token, NULL, 10); /* the position of "v/vt/vn" */
                if (v < 0) v += (long)mesh->vertex_count + 1; /* relative index */
                if (v < 1) {
                    fprintf(stderr, "%s: bad face corner %s\n", path, token);
                    fclose(file);
                    return 0;
                }
                corners[n++] = (unsigned int)(v - 1);
            }
            for (i = 1; i + 1 < n; ++i) {
                mesh->indices = grow(mesh->indices, &mesh->index_capacity, mesh->index_count + 3, sizeof(unsigned int));
                mesh->indices[mesh->index_count++] = corners[0];
                mesh->indices[mesh->index_count++] = corners[i];
                mesh->indices[mesh->index_count++] = corners[i + 1];
            }
        }
    }
    fclose(file);
    return 1;
}

/* CPU time of the process: the library runs on the calling thread, and CPU time is
   less disturbed than wall time by other programs on a busy machine. */
static double now_ms(void) {
    struct timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return t.tv_sec * 1e3 + t.tv_nsec / 1e6;
}

static int compare_doubles(const void* a, const void* b) {
    double x = *(const double*)a, y = *(const double*)b;
    return (x > y) - (x < y);
}

static int fail(const char* what) {
    fprintf(stderr, "%s: %s\n", what, stripkit_last_error());
    return 1;
}

int main(int argc, char** argv) {
    stripkit_options options = stripkit_options_default();
    const char* path = NULL;
    int use_mesh = 0, runs = 0, i;
    obj_mesh mesh;
    unsigned int* strip;
    unsigned int* back;
    int64_t written, drawn;
    stripkit_mesh_result result = {0};
    size_t strip_count;

    for (i = 1; i < argc; ++i) {
        if (!strcmp(argv[i], "--mesh")) use_mesh = 1;
        else if (!strcmp(argv[i], "--algorithm") && i + 1 < argc) options.algorithm = (uint32_t)atoi(argv[++i]);
        else if (!strcmp(argv[i], "--join") && i + 1 < argc) options.join = (uint32_t)atoi(argv[++i]);
        else if (!strcmp(argv[i], "--time") && i + 1 < argc) runs = atoi(argv[++i]);
        else path = argv[i];
    }
    if (!path) {
        fprintf(stderr, "usage: %s [--mesh] [--algorithm N] [--join N] [--time RUNS] mesh.obj\n", argv[0]);
        return 2;
    }
    if (!read_obj(path, &mesh)) return 2;

    if (runs > 0) {
        double* times = malloc(sizeof(double) * (size_t)runs);
        size_t bound = stripkit_stripify_bound(mesh.index_count);
        strip = malloc(sizeof(unsigned int) * bound);
        for (i = 0; i < runs; ++i) {
            double start = now_ms();
            written = stripkit_stripify(strip, bound, mesh.indices, mesh.index_count, mesh.vertex_count, 0xFFFFFFFFu, &options);
            times[i] = now_ms() - start;
            if (written < 0) return fail("stripkit_stripify");
        }
        qsort(times, (size_t)runs, sizeof(double), compare_doubles);
        printf("c %zu triangles: median %.3f ms CPU over %d runs (%lld indices)\n", mesh.index_count / 3,
               times[runs / 2], runs, (long long)written);
        free(times);
        free(strip);
        return 0;
    }

    if (use_mesh) {
        if (stripkit_stripify_mesh(mesh.positions, mesh.vertex_count, mesh.indices, mesh.index_count, &options, &result) != STRIPKIT_OK)
            return fail("stripkit_stripify_mesh");
        strip = (unsigned int*)result.indices;
        strip_count = result.index_count;
    } else {
        size_t bound = stripkit_stripify_bound(mesh.index_count);
        strip = malloc(sizeof(unsigned int) * bound);
        written = stripkit_stripify(strip, bound, mesh.indices, mesh.index_count, mesh.vertex_count, 0xFFFFFFFFu, &options);
        if (written < 0) return fail("stripkit_stripify");
        strip_count = (size_t)written;
    }

    /* The strips draw as many triangles as the input (the library verified them). */
    back = malloc(sizeof(unsigned int) * (stripkit_unstripify_bound(strip_count) + 1));
    drawn = stripkit_unstripify(back, stripkit_unstripify_bound(strip_count), strip, strip_count, 0xFFFFFFFFu);
    if (drawn < 0) return fail("stripkit_unstripify");
    if ((size_t)drawn != 3 * (use_mesh ? result.triangle_count : mesh.index_count / 3)) {
        fprintf(stderr, "the strips draw %lld indices of triangles, expected %zu\n", (long long)drawn, mesh.index_count);
        return 1;
    }

    for (i = 0; (size_t)i < strip_count; ++i) printf("%u\n", strip[i]);
    if (use_mesh) {
        size_t k;
        for (k = 0; k < result.added_count; ++k) {
            uint32_t bits[3];
            memcpy(bits, result.added_positions + 3 * k, sizeof bits);
            printf("added %08x %08x %08x %u %u\n", bits[0], bits[1], bits[2], result.added_from[2 * k],
                   result.added_from[2 * k + 1]);
        }
        stripkit_mesh_result_free(&result);
    } else {
        free(strip);
    }
    free(back);
    free(mesh.positions);
    free(mesh.indices);
    return 0;
}
