#!/usr/bin/env bash
# Packages the published crates and checks what a user of crates.io would get.
#
#   scripts/package-check.sh            what scripts/test (so CI) runs:
#       1. `cargo package` of the four crates in dependency order, verified: each one
#          is built from its .crate against the others packaged beside it (cargo's
#          local registry overlay, so nothing needs to be on crates.io yet);
#       2. each .crate holds only the files the rules allow (sources, README, licence
#          texts, manifests), and its size is printed.
#   scripts/package-check.sh --fresh    the release check (docs/release.md, step 4):
#       1 and 2, then 3. a fresh directory outside the repository holding only the
#          .crate files, unpacked: `cargo install --path` on the CLI crate with its
#          stripkit dependencies pointed at the unpacked crates ([patch.crates-io]);
#          the installed binary strips assets/spot.obj. A release build: minutes.
#   scripts/package-check.sh --quick    1 without verification, and 2: seconds.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
quick=0
fresh_check=0
case "${1:-}" in
    --quick) quick=1 ;;
    --fresh) fresh_check=1 ;;
    "") ;;
    *) echo "usage: scripts/package-check.sh [--quick | --fresh]" >&2; exit 2 ;;
esac

# Dependency order: each crate needs only those before it.
crates=(stripkit-matching stripkit stripkit-render stripkit-cli)
version=$(cargo metadata --no-deps --format-version 1 \
    | python3 -c 'import json,sys; print(next(p["version"] for p in json.load(sys.stdin)["packages"] if p["name"]=="stripkit"))')
pkg_args=()
for c in "${crates[@]}"; do pkg_args+=(-p "$c"); done
verify=()
[ $quick = 1 ] && verify=(--no-verify)
# Verification unpacks each package from cargo's local registry overlay into
# CARGO_HOME/registry/src/-HASH/NAME-VERSION and reuses that folder while the version is
# unchanged, so a later run would build the dependents against the first run's sources:
# remove those copies of our four crates first.
for c in "${crates[@]}"; do
    rm -rf "${CARGO_HOME:-$HOME/.cargo}"/registry/src/-*/"$c-$version"
done
# Cargo also takes a registry crate's compiled output as current while its version is
# unchanged (a registry's sources never change), so a second run would link the CLI
# against the first run's stripkit: the packages are built in a target folder of their
# own, from which our crates' outputs are removed each time (the third-party ones stay).
verify_target="$root/target/package-verify"
rm -rf "$verify_target"/debug/.fingerprint/stripkit-* "$verify_target"/debug/deps/*stripkit* \
    "$verify_target"/debug/build/stripkit-*
packages="$verify_target/package"
# Uncommitted work is packaged as it is (CI checks out a clean tree anyway).
start=$SECONDS
CARGO_TARGET_DIR="$verify_target" cargo package "${pkg_args[@]}" "${verify[@]}" --allow-dirty --quiet 2> >(grep -v -E "^warning: ignoring (test|example|bench) " >&2)
echo "cargo package ${verify[*]:-(verified)}: $((SECONDS - start)) s"

# 2. The files in each package, against the allowed patterns.
status=0
for c in "${crates[@]}"; do
    file="$packages/$c-$version.crate"
    list=$(tar tzf "$file" | sed "s|^$c-$version/||")
    bad=$(grep -v -E <<<"$list" \
        '^(Cargo\.toml|Cargo\.toml\.orig|Cargo\.lock|\.cargo_vcs_info\.json|README\.md|LICENSE-MIT|LICENSE-APACHE|src/.*\.rs|src/cmd/view/[a-z-]+\.(html|css|js)|examples/[a-z_]+\.rs)$' || true)
    if [ -n "$bad" ]; then
        echo "error: $c's package holds files outside the rules of docs/release.md:" >&2
        echo "$bad" >&2
        status=1
    fi
    for need in README.md LICENSE-MIT LICENSE-APACHE; do
        grep -qx "$need" <<<"$list" || { echo "error: $c's package lacks $need" >&2; status=1; }
    done
    files=$(wc -l <<<"$list")
    unpacked=$(tar xzf "$file" -O | wc -c)
    printf '%-18s %3d files, %8d bytes unpacked, %7d bytes .crate\n' "$c" "$files" "$unpacked" "$(stat -c %s "$file")"
    # crates.io refuses a package over 10 MiB; ours are far below, and should stay so.
    if [ "$(stat -c %s "$file")" -gt 1048576 ]; then
        echo "error: $c's package is over 1 MiB" >&2
        status=1
    fi
done
[ $status = 0 ] || exit $status
[ $fresh_check = 1 ] || exit 0

# 3. Only the .crate files, in a directory no workspace contains.
fresh=$(mktemp -d /tmp/stripkit-package-check.XXXXXX)
trap 'rm -rf "$fresh"' EXIT
for c in "${crates[@]}"; do
    cp "$packages/$c-$version.crate" "$fresh/"
    tar xzf "$fresh/$c-$version.crate" -C "$fresh"
done
patches=()
for c in stripkit-matching stripkit stripkit-render; do
    patches+=(--config "patch.crates-io.$c.path=\"$fresh/$c-$version\"")
done
start=$SECONDS
# The build goes into this worktree's target/ (kept between runs); the binary into $fresh.
(cd "$fresh" && CARGO_TARGET_DIR="$root/target/package-check" cargo install --quiet \
    "${patches[@]}" --path "stripkit-cli-$version" --root "$fresh/install")
echo "cargo install --path stripkit-cli-$version (from the unpacked crates): $((SECONDS - start)) s"
# Every stripkit crate of the build must be an unpacked one in $fresh, none from the
# repository or a registry.
(cd "$fresh/stripkit-cli-$version" && cargo metadata --format-version 1 "${patches[@]}") \
    | python3 -c '
import json, sys
fresh = sys.argv[1]
meta = json.load(sys.stdin)
ours = [p for p in meta["packages"] if p["name"].startswith("stripkit")]
wrong = [p["name"] + " " + p["manifest_path"] for p in ours if not p["manifest_path"].startswith(fresh + "/")]
if wrong or len(ours) != 4:
    sys.exit("error: stripkit crates not from the unpacked packages: " + ", ".join(wrong))
print("stripkit crates built from the unpacked packages:", ", ".join(sorted(p["name"] for p in ours)))
' "$fresh"
cp "$root/assets/spot.obj" "$fresh/spot.obj"
(cd "$fresh" && ./install/bin/stripkit strip spot.obj -o spot_strips.glb)
echo "spot_strips.glb: $(stat -c %s "$fresh/spot_strips.glb") bytes"
