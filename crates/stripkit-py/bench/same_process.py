"""Python call overhead measured in one process: the binding's `stripify` against the
same library call reached through the C library's ABI (ctypes adds microseconds),
alternated on the same input, so both see the same heap and the same load. Separate
processes differ by their allocators' state (see docs/experiments/python.md).

    cargo build --release -p stripkit-c
    pip install ./crates/stripkit-py        # a release build
    python crates/stripkit-py/bench/same_process.py MESH target/release/libstripkit.so CALLS
"""
import ctypes, statistics, sys, time
import numpy as np, stripkit
lib = ctypes.CDLL(sys.argv[2])
lib.stripkit_stripify.restype = ctypes.c_int64
lib.stripkit_stripify.argtypes = [ctypes.c_void_p, ctypes.c_size_t, ctypes.c_void_p, ctypes.c_size_t, ctypes.c_size_t, ctypes.c_uint, ctypes.c_void_p]
lib.stripkit_stripify_bound.restype = ctypes.c_size_t
m = stripkit.read(sys.argv[1]); tris = np.ascontiguousarray(m.triangles, dtype=np.uint32); n = len(m.vertices)
flat = tris.reshape(-1)
dest = np.empty(lib.stripkit_stripify_bound(ctypes.c_size_t(flat.size)), dtype=np.uint32)
def c_call():
    k = lib.stripkit_stripify(dest.ctypes.data, dest.size, flat.ctypes.data, flat.size, n, 0xFFFFFFFF, None)
    assert k > 0
    return dest[:k]
def py_call():
    return stripkit.stripify(tris, n)
assert np.array_equal(c_call(), py_call())
rc, rp = [], []
for _ in range(int(sys.argv[3])):
    for f, acc in ((c_call, rc), (py_call, rp)):
        t = time.perf_counter(); f(); acc.append((time.perf_counter() - t) * 1e3)
c, p = statistics.median(rc), statistics.median(rp)
print(f"{sys.argv[1]}: {len(tris)} triangles, {len(rc)} alternated calls each: C ABI {c:.2f} ms, Python {p:.2f} ms, Python/C {p/c:.4f}")
