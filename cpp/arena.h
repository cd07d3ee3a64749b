// The arena a traced kernel records into (rust/plugin/src/traced.rs): an abstract class, so that the
// cxx glue compiled by build.rs needs no Mitsuba or Dr.Jit headers and one Rust build serves
// every Dr.Jit backend. Each method performs one Dr.Jit operation on the values stored at the
// given indices and returns the index of the result; comparisons return indices into a
// separate mask store. Methods are `const` because cxx lends Rust a shared `&Arena`; the
// stores are `mutable` in the implementation (cpp/arena_impl.h). One arena = one trace on one
// thread.
#pragma once
#include <cstdint>

namespace matte {

class Arena {
public:
    virtual ~Arena() = default;
    virtual uint32_t lit(float v) const = 0;
    virtual uint32_t add(uint32_t a, uint32_t b) const = 0;
    virtual uint32_t sub(uint32_t a, uint32_t b) const = 0;
    virtual uint32_t mul(uint32_t a, uint32_t b) const = 0;
    virtual uint32_t div(uint32_t a, uint32_t b) const = 0;
    virtual uint32_t minimum(uint32_t a, uint32_t b) const = 0;
    virtual uint32_t maximum(uint32_t a, uint32_t b) const = 0;
    virtual uint32_t neg(uint32_t a) const = 0;
    virtual uint32_t abs(uint32_t a) const = 0;
    virtual uint32_t sqrt(uint32_t a) const = 0;
    virtual uint32_t floor(uint32_t a) const = 0;
    virtual uint32_t fma(uint32_t a, uint32_t b, uint32_t c) const = 0;
    virtual void sincos(uint32_t a, uint32_t &s, uint32_t &c) const = 0;
    virtual uint32_t exp(uint32_t a) const = 0;
    virtual uint32_t lt(uint32_t a, uint32_t b) const = 0;
    virtual uint32_t le(uint32_t a, uint32_t b) const = 0;
    virtual uint32_t gt(uint32_t a, uint32_t b) const = 0;
    virtual uint32_t eq(uint32_t a, uint32_t b) const = 0;
    virtual uint32_t mask_lit(bool v) const = 0;
    virtual uint32_t mask_and(uint32_t a, uint32_t b) const = 0;
    virtual uint32_t mask_or(uint32_t a, uint32_t b) const = 0;
    virtual uint32_t mask_not(uint32_t a) const = 0;
    virtual uint32_t select(uint32_t m, uint32_t t, uint32_t f) const = 0;
    /// `table[idx + offset]` from the buffer the plugin registered as table number `table`
    /// (`idx` an integer-valued float, `offset` a constant).
    virtual uint32_t gather(uint32_t table, uint32_t idx, uint32_t offset) const = 0;
    /// The packet `table[8 idx .. 8 idx + 8]` (Dr.Jit's packet gather): the eight values are
    /// stored as consecutive entries; returns the index of the first.
    virtual uint32_t gather8(uint32_t table, uint32_t idx) const = 0;
};

}  // namespace matte
