// strip_obj_cpp: the C++ side of stripkit's C API. Strips an OBJ's triangles with
// 16-bit indices (stripkit_stripify16) when the mesh has at most 65,535 vertices, with
// 32-bit ones otherwise, and prints one index per line, the restart index as
// 4294967295 either way (so the output compares with the 32-bit programs').
//
//   strip_obj_cpp mesh.obj
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "stripkit.h"

namespace {

struct ObjMesh {
    std::size_t vertex_count = 0;
    std::vector<unsigned int> indices;  // faces fanned from their first corner
};

bool read_obj(const char* path, ObjMesh& mesh) {
    std::ifstream in(path);
    if (!in) return false;
    std::string line;
    while (std::getline(in, line)) {
        if (line.rfind("v ", 0) == 0) {
            ++mesh.vertex_count;
        } else if (line.rfind("f ", 0) == 0) {
            std::istringstream corners(line.substr(2));
            std::vector<unsigned int> face;
            std::string corner;
            while (corners >> corner) {
                long v = std::stol(corner);  // the position of "v/vt/vn"
                if (v < 0) v += static_cast<long>(mesh.vertex_count) + 1;
                if (v < 1) return false;
                face.push_back(static_cast<unsigned int>(v - 1));
            }
            for (std::size_t i = 1; i + 1 < face.size(); ++i)
                mesh.indices.insert(mesh.indices.end(), {face[0], face[i], face[i + 1]});
        }
    }
    return true;
}

template <typename Index>
std::vector<Index> narrow(const std::vector<unsigned int>& indices) {
    return std::vector<Index>(indices.begin(), indices.end());
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: %s mesh.obj\n", argv[0]);
        return 2;
    }
    ObjMesh mesh;
    if (!read_obj(argv[1], mesh)) {
        std::fprintf(stderr, "cannot read %s\n", argv[1]);
        return 2;
    }
    const stripkit_options options = stripkit_options_default();
    std::vector<unsigned int> strip(stripkit_stripify_bound(mesh.indices.size()));
    std::int64_t written;
    if (mesh.vertex_count <= 0xFFFF) {
        std::vector<unsigned short> in16 = narrow<unsigned short>(mesh.indices);
        std::vector<unsigned short> out16(strip.size());
        written = stripkit_stripify16(out16.data(), out16.size(), in16.data(), in16.size(), mesh.vertex_count,
                                      0xFFFF, &options);
        for (std::int64_t i = 0; i < written; ++i)
            strip[i] = out16[i] == 0xFFFF ? 0xFFFFFFFFu : out16[i];
    } else {
        written = stripkit_stripify(strip.data(), strip.size(), mesh.indices.data(), mesh.indices.size(),
                                    mesh.vertex_count, 0xFFFFFFFFu, &options);
    }
    if (written < 0) {
        std::fprintf(stderr, "stripify failed (%lld): %s\n", static_cast<long long>(written), stripkit_last_error());
        return 1;
    }
    for (std::int64_t i = 0; i < written; ++i) std::printf("%u\n", strip[i]);
    return 0;
}
