#!/usr/bin/env bash
# Cortex-M4F (thumbv7em-none-eabihf) footprint of the C API: size of a
# bare-metal image that calls a group of functions minus an empty baseline
# image (same profile: opt-level "s", LTO, panic = "abort"; linked by
# rust-lld), then links of an image that calls every exported C function with
# the `prove-no-panic` panic handler (opt-level "s" and 3), which succeed only
# if no panic path survives in any C API function.
set -euo pipefail
cd "$(dirname "$0")"
t=thumbv7em-none-eabihf
img=target/$t/release/size-check
# Quiet builds; the only expected warning is that cdylib does not exist on this target.
build() { cargo build --release --target $t -q "$@" 2> >(grep -v -e 'dropping unsupported crate type' -e '^$' >&2); }
flash() { llvm-size "$img" 2>/dev/null | awk 'NR==2 {print $1 + $2}' || size "$img" | awk 'NR==2 {print $1 + $2}'; }
build
base=$(flash)
printf "%-58s %6s bytes flash (text + data)\n" "baseline image (empty reset handler)" "$base"
for f in als correction brdf material openpbr rgb; do
    case $f in
        als) what="ALS: from_reference + set_spectral_correction + lux" ;;
        correction) what="ALS + spectral correction (CIE V, D65, A; 1 nm integrals)" ;;
        brdf) what="every BRDF plugin: eval/pdf/sample, single + batched" ;;
        material) what="materials (sum, mix, coated) of every plugin, all calls" ;;
        openpbr) what="OpenPBR reflection: defaults, new, all calls" ;;
        rgb) what="colour: _rgb constructors + every _rgb call (all handles)" ;;
    esac
    build --features "$f"
    size_f=$(flash)
    printf "%-58s %6s bytes flash (+%d over baseline)\n" "$what" "$size_f" $(( size_f - base ))
    if [ "$f" = als ]; then
        printf "%-58s %6s\n" "  soft-float f64 helpers (__aeabi_d*) in the ALS image:" \
            "$( (llvm-nm "$img" 2>/dev/null || nm "$img") | grep -c '__aeabi_d' || true)"
    fi
done
# The proof: an image calling every exported C function (all groups and `others`), at opt-level "s" and 3.
build --features correction,brdf,material,openpbr,rgb,others,prove-no-panic
cargo build --profile release-o3 --target $t -q --features correction,brdf,material,openpbr,rgb,others,prove-no-panic \
    2> >(grep -v -e 'dropping unsupported crate type' -e '^$' >&2)
echo "prove-no-panic: the image calling every C API function links at opt-level \"s\" and 3, so no panic path survives"
