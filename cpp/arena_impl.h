// matte::Arena (cpp/arena.h) for one Dr.Jit `Float` type: dr::DiffArray<LLVM, float> in the
// llvm_ad_* variants, the CUDA one in cuda_ad_*. Every method runs the ordinary Dr.Jit
// operation on the stored arrays, so in symbolic mode it records IR, in evaluated mode it
// schedules work and with autodiff it records the AD graph. Entries live until the arena (a
// stack object in each eval/sample) is destroyed, which releases their references; results
// are copied out before.
#pragma once

#include "arena.h"
#include <drjit/array.h>
#include <vector>

namespace matte {

template <typename Float>
class ArenaT final : public Arena {
public:
    using Mask = drjit::mask_t<Float>;
    using UInt32 = drjit::uint32_array_t<Float>;

    explicit ArenaT(const std::vector<Float> *tables = nullptr) : m_tables(tables) {
        m_f.reserve(256);
        m_m.reserve(64);
    }

    uint32_t push(Float v) const {
        m_f.push_back(std::move(v));
        return (uint32_t) m_f.size() - 1;
    }
    /// The value at `i`; an index the arena never returned gives 0 (never a crash).
    Float get(uint32_t i) const { return i < m_f.size() ? m_f[i] : Float(0.f); }

    uint32_t lit(float v) const override { return push(Float(v)); }
    uint32_t add(uint32_t a, uint32_t b) const override { return push(f(a) + f(b)); }
    uint32_t sub(uint32_t a, uint32_t b) const override { return push(f(a) - f(b)); }
    uint32_t mul(uint32_t a, uint32_t b) const override { return push(f(a) * f(b)); }
    uint32_t div(uint32_t a, uint32_t b) const override { return push(f(a) / f(b)); }
    // A NaN operand gives the other one, as the kernels' clamps need (rust/brdf/src/real.rs:
    // `Real::min`): IEEE 754 minNum/maxNum, see min_num below.
    uint32_t minimum(uint32_t a, uint32_t b) const override { return push(min_num(f(a), f(b))); }
    uint32_t maximum(uint32_t a, uint32_t b) const override { return push(max_num(f(a), f(b))); }
    uint32_t neg(uint32_t a) const override { return push(-f(a)); }
    uint32_t abs(uint32_t a) const override { return push(drjit::abs(f(a))); }
    uint32_t sqrt(uint32_t a) const override { return push(drjit::sqrt(f(a))); }
    uint32_t floor(uint32_t a) const override { return push(drjit::floor(f(a))); }
    uint32_t fma(uint32_t a, uint32_t b, uint32_t c) const override { return push(drjit::fmadd(f(a), f(b), f(c))); }
    uint32_t exp(uint32_t a) const override { return push(drjit::exp(f(a))); }
    void sincos(uint32_t a, uint32_t &s, uint32_t &c) const override {
        auto [sv, cv] = drjit::sincos(f(a));
        s = push(std::move(sv));
        c = push(std::move(cv));
    }
    uint32_t lt(uint32_t a, uint32_t b) const override { return push_mask(f(a) < f(b)); }
    uint32_t le(uint32_t a, uint32_t b) const override { return push_mask(f(a) <= f(b)); }
    uint32_t gt(uint32_t a, uint32_t b) const override { return push_mask(f(a) > f(b)); }
    uint32_t eq(uint32_t a, uint32_t b) const override { return push_mask(f(a) == f(b)); }
    uint32_t mask_lit(bool v) const override { return push_mask(Mask(v)); }
    uint32_t mask_and(uint32_t a, uint32_t b) const override { return push_mask(m(a) && m(b)); }
    uint32_t mask_or(uint32_t a, uint32_t b) const override { return push_mask(m(a) || m(b)); }
    uint32_t mask_not(uint32_t a) const override { return push_mask(!m(a)); }
    uint32_t select(uint32_t mi, uint32_t t, uint32_t e) const override {
        return push(drjit::select(m(mi), f(t), f(e)));
    }
    // Both gathers clamp their index to the table as an integer: the index comes from a float
    // (an integer-valued one, clamped by the lookups), and a lane whose float was NaN converts
    // to an arbitrary integer. The packet load has no bounds check at all (not even in Dr.Jit's
    // debug mode), so such a lane would read outside the table.
    uint32_t gather(uint32_t table, uint32_t idx, uint32_t offset) const override {
        const Float *source = table_of(table, 1);
        if (!source)
            return push(Float(0.f));
        UInt32 last = UInt32((uint32_t) drjit::width(*source) - 1);
        return push(drjit::gather<Float>(*source, drjit::minimum(UInt32(f(idx)) + offset, last)));
    }
    uint32_t gather8(uint32_t table, uint32_t idx) const override {
        uint32_t first = (uint32_t) m_f.size();
        const Float *source = table_of(table, 8);
        if (!source) {
            for (int k = 0; k < 8; ++k)
                push(Float(0.f));
            return first;
        }
        // A target of 8 Floats from a flat source: jit_var_gather_packet / ad_var_gather_packet.
        UInt32 last = UInt32((uint32_t) (drjit::width(*source) / 8) - 1);
        auto v = drjit::gather<drjit::Array<Float, 8>>(*source, drjit::minimum(UInt32(f(idx)), last));
        for (size_t k = 0; k < 8; ++k)
            push(std::move(v[k]));
        return first;
    }

private:
#if DRJIT_VERSION_MAJOR > 1 || DRJIT_VERSION_MINOR >= 5
    // Dr.Jit's fmin/fmax. Its minimum/maximum propagate NaN since Dr.Jit 1.5.0.
    static Float min_num(const Float &a, const Float &b) { return drjit::fmin(a, b); }
    static Float max_num(const Float &a, const Float &b) { return drjit::fmax(a, b); }
#else
    // Dr.Jit before 1.5.0 (Mitsuba 3.7.0 to 3.9.0) has no fmin/fmax, and its minimum/maximum do
    // not say what a NaN operand gives: the operand that is not NaN, written out.
    static Float min_num(const Float &a, const Float &b) { return drjit::select((a <= b) || drjit::isnan(b), a, b); }
    static Float max_num(const Float &a, const Float &b) { return drjit::select((a >= b) || drjit::isnan(b), a, b); }
#endif
    /// The registered table number `table` when it holds at least `n` values, else null.
    const Float *table_of(uint32_t table, size_t n) const {
        if (!m_tables || table >= m_tables->size() || drjit::width((*m_tables)[table]) < n)
            return nullptr;
        return &(*m_tables)[table];
    }
    uint32_t push_mask(Mask v) const {
        m_m.push_back(std::move(v));
        return (uint32_t) m_m.size() - 1;
    }
    // Copies (cheap: a JIT/AD index and a reference count) so that push_back may reallocate.
    Float f(uint32_t i) const { return get(i); }
    Mask m(uint32_t i) const { return i < m_m.size() ? m_m[i] : Mask(false); }

    mutable std::vector<Float> m_f;
    mutable std::vector<Mask> m_m;
    const std::vector<Float> *m_tables;
};

}  // namespace matte
