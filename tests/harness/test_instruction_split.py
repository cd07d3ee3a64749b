"""validation/experiments/instruction_split.py's reading of callgrind's listing (the profiling itself needs
valgrind and minutes per scene: docs/performance.md)."""

from validation.experiments import instruction_split

# The shape of `callgrind_annotate --inclusive=no --auto=no` output, lines taken from real runs.
LISTING = """\
--------------------------------------------------------------------------------
Ir                    file:function
--------------------------------------------------------------------------------
224,928,091 ( 6.18%)  ???:0x0000000007ff6240 [???]
221,319,219 ( 6.08%)  ???:embree::avx2::BVHNIntersectorKHybrid<8, 8, 1, false, embree::avx2::ArrayIntersectorK_1<8>, true>
 62,448,747 (10.26%)  ???:0x0000000001960660 [/usr/lib/x86_64-linux-gnu/libembree3.so.3.13.5]
 14,953,086 ( 0.41%)  ???:0x0000000007ffa4f0'2 [???]
 24,724,216 ( 4.06%)  /work/main/rust/render/integrator/path.rs:matte_render::integrator::one_path::render_tile
  5,992,896 ( 0.98%)  ???:rtcIntersect1 [/usr/lib/x86_64-linux-gnu/libembree3.so.3.13.5]
  1,000 ( 0.00%)  ???:0x00000000010e3120 [/usr/lib/x86_64-linux-gnu/libLLVM.so.19.1]
"""


def test_listing_is_split_into_embree_jit_kernels_and_the_rest():
    got = instruction_split.split_listing(LISTING)
    assert got == {
        "embree": 221_319_219 + 62_448_747 + 5_992_896,
        "jit": 224_928_091 + 14_953_086,
        "rest": 24_724_216 + 1_000,
    }


def test_header_totals_are_not_counted():
    listing = "3,640,110,263 (100.0%)  PROGRAM TOTALS\n" + LISTING
    assert sum(instruction_split.split_listing(listing).values()) == sum(
        instruction_split.split_listing(LISTING).values()
    )
