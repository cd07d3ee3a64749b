/*
 * matte's Mitsuba 3 BSDF: one class for every matte model, whose math is the Rust kernels
 * (rust/brdf/) called through the cxx bridge (rust/ffi/). Mitsuba loads the plugin under the
 * name of the `<bsdf type="...">` (lambert, oren_nayar, eon, wolff, ginneken); that name
 * selects the model.
 *
 * Parameters (brdf-models.md; all optional):
 *
 *   reflectance  spectrum or texture    albedo parameter ρ (default 0.5), evaluated per channel
 *   oren_nayar:  sigma (float, radians, 0.3), model ("qualitative" | "full")
 *   eon:         roughness (float in [0, 1], 0.3)
 *   wolff:       int_ior, ext_ior (float or a Mitsuba IOR name, 1.4 / 1.0),
 *                normalization ("physical" | "normal" | "raw")
 *   ginneken:    roughness (float > 0, rms slope, 0.3), shadowing ("vginneken" | "height_correlated")
 *
 * Every model is one-sided (use `twosided` for two-sided surfaces) and is sampled
 * cosine-weighted. `eval` returns f·cos θo as Mitsuba expects; the kernels return f.
 *
 * Variants: scalar_rgb and scalar_spectral call the kernels per lane. The llvm variants
 * (llvm_ad_rgb, llvm_ad_mono, llvm_ad_spectral) run in Dr.Jit's *evaluated* mode: the
 * inputs are evaluated, their host buffers handed to a Rust batch function and the results
 * loaded back. A Rust function cannot be traced into a Dr.Jit kernel, so calling the
 * plugin inside a symbolic loop or call raises an error that says which flags to switch off.
 * Gradients do not flow through the kernels: parameters are exposed as non-differentiable.
 */
#pragma once

#include <mitsuba/core/properties.h>
#include <mitsuba/core/string.h>
#include <mitsuba/render/bsdf.h>
#include <mitsuba/render/texture.h>

#include "rust/cxx.h"  // rust::Error (the generated header declares only what it uses)
#include "matte/rust/ffi/bridge.rs.h"

#include <optional>
#include <vector>

NAMESPACE_BEGIN(mitsuba)

template <typename Float, typename Spectrum>
class MatteBSDF final : public BSDF<Float, Spectrum> {
public:
    MI_IMPORT_BASE(BSDF, m_flags, m_components)
    MI_IMPORT_TYPES(Texture)

    MatteBSDF(const Properties &props) : Base(props), m_kind(props.plugin_name()) {
        m_reflectance = props.get_texture<Texture>("reflectance", .5f);
        // Hand every scalar property to the Rust parser, which validates names and values
        // (one parser for plugin, renderer and CLI). Anything else stays unqueried, so
        // Mitsuba reports it as an unreferenced property.
        std::vector<std::string> names;
        for (const auto &p : props)
            names.emplace_back(p.name());
        for (const std::string &name : names) {
            if (name == "reflectance")
                continue;
            switch (props.type(name)) {
                case Properties::Type::Float:
                case Properties::Type::Integer:
                    m_params.push_back(number_param(name, props.get<double>(name)));
                    break;
                case Properties::Type::String:
                    m_params.push_back(text_param(name, props.get<std::string>(name)));
                    break;
                case Properties::Type::Bool:
                    m_params.push_back(text_param(name, props.get<bool>(name) ? "true" : "false"));
                    break;
                default:
                    break;
            }
        }
        build_model();
        m_flags = BSDFFlags::DiffuseReflection | BSDFFlags::FrontSide;
        m_components.push_back(m_flags);
    }

    void traverse(TraversalCallback *cb) override {
        cb->put("reflectance", m_reflectance, ParamFlags::NonDifferentiable);
        for (auto &[name, value] : m_numeric)
            cb->put(name, value, ParamFlags::NonDifferentiable);
    }

    void parameters_changed(const std::vector<std::string> & /*keys*/ = {}) override {
        // Numeric parameters may have been edited through mi.traverse(): rebuild the model
        // with the new values (validated again by the kernels).
        for (auto &[name, value] : m_numeric) {
            bool found = false;
            for (auto &p : m_params)
                if (std::string(p.name) == name) {
                    p.is_number = true;
                    p.number = (double) value;
                    found = true;
                }
            if (!found)
                m_params.push_back(number_param(name, (double) value));
        }
        build_model();
    }

    std::pair<BSDFSample3f, Spectrum> sample(const BSDFContext &ctx,
                                             const SurfaceInteraction3f &si,
                                             Float /* sample1 */,
                                             const Point2f &sample2,
                                             Mask active) const override {
        MI_MASKED_FUNCTION(ProfilerPhase::BSDFSample, active);
        Float cos_theta_i = Frame3f::cos_theta(si.wi);
        BSDFSample3f bs = dr::zeros<BSDFSample3f>();
        active &= cos_theta_i > 0.f;
        if (unlikely(dr::none_or<false>(active) ||
                     !ctx.is_enabled(BSDFFlags::DiffuseReflection)))
            return { bs, 0.f };

        UnpolarizedSpectrum value = m_reflectance->eval(si, active);
        if constexpr (!dr::is_jit_v<Float>) {
            matte::ffi::Channels weight{};
            matte::ffi::Vec3f wo{ 0.f, 0.f, 1.f };
            float pdf = (*m_model)->sample(to_ffi(si.wi), (float) sample2.x(), (float) sample2.y(),
                                           to_channels(value), wo, weight);
            bs.wo = Vector3f(wo.x, wo.y, wo.z);
            bs.pdf = pdf;
            for (size_t c = 0; c < Channels; ++c)
                value[c] = weight.v[c];
        } else {
            require_evaluated_mode("sample");
            size_t n = dr::width(si.wi, sample2, value, active);
            MaskD mask = scheduled_mask(active);
            std::vector<FloatD> in = evaluated(si.wi, sample2, value);
            std::vector<FloatD> out = allocated(n, Channels + 4);  // weight, pdf, wo
            matte::ffi::LanesIn lanes_in = lanes(in, 2, mask);  // wi, u (2-D sample), reflectance
            matte::ffi::LanesOut lanes_out = lanes(out, n);
            (*m_model)->sample_lanes(lanes_in, lanes_out);
            for (size_t c = 0; c < Channels; ++c)
                value[c] = Float(out[c]);
            bs.pdf = Float(out[Channels]);
            bs.wo = Vector3f(Float(out[Channels + 1]), Float(out[Channels + 2]), Float(out[Channels + 3]));
        }
        bs.eta = 1.f;
        bs.sampled_type = +BSDFFlags::DiffuseReflection;
        bs.sampled_component = 0;
        return { bs, depolarizer<Spectrum>(value) & (active && bs.pdf > 0.f) };
    }

    Spectrum eval(const BSDFContext &ctx, const SurfaceInteraction3f &si,
                  const Vector3f &wo, Mask active) const override {
        MI_MASKED_FUNCTION(ProfilerPhase::BSDFEvaluate, active);
        if (!ctx.is_enabled(BSDFFlags::DiffuseReflection))
            return 0.f;
        return eval_pdf_impl(si, wo, active).first;
    }

    Float pdf(const BSDFContext &ctx, const SurfaceInteraction3f &si,
              const Vector3f &wo, Mask active) const override {
        MI_MASKED_FUNCTION(ProfilerPhase::BSDFEvaluate, active);
        if (!ctx.is_enabled(BSDFFlags::DiffuseReflection))
            return 0.f;
        if constexpr (!dr::is_jit_v<Float>) {
            if (!(active && Frame3f::cos_theta(si.wi) > 0.f && Frame3f::cos_theta(wo) > 0.f))
                return 0.f;
            return (*m_model)->pdf(to_ffi(si.wi), to_ffi(wo));
        } else {
            return eval_pdf_impl(si, wo, active).second;
        }
    }

    std::pair<Spectrum, Float> eval_pdf(const BSDFContext &ctx,
                                        const SurfaceInteraction3f &si,
                                        const Vector3f &wo,
                                        Mask active) const override {
        MI_MASKED_FUNCTION(ProfilerPhase::BSDFEvaluate, active);
        if (!ctx.is_enabled(BSDFFlags::DiffuseReflection))
            return { 0.f, 0.f };
        return eval_pdf_impl(si, wo, active);
    }

    Spectrum eval_diffuse_reflectance(const SurfaceInteraction3f &si,
                                      Mask active) const override {
        return m_reflectance->eval(si, active);
    }

    std::string to_string() const override {
        std::ostringstream oss;
        oss << "MatteBSDF[" << std::endl
            << "  type = \"" << m_kind << "\"," << std::endl
            << "  reflectance = " << string::indent(m_reflectance) << "," << std::endl;
        for (const auto &p : (*m_model)->describe_parameters()) {
            oss << "  " << std::string(p.name) << " = ";
            if (p.is_number)
                oss << p.number;
            else
                oss << "\"" << std::string(p.text) << "\"";
            oss << "," << std::endl;
        }
        oss << "]";
        return oss.str();
    }

    MI_DECLARE_CLASS(MatteBSDF)

private:
    static constexpr size_t Channels = dr::size_v<UnpolarizedSpectrum>;
    using FloatD = dr::detached_t<Float>;
    using MaskD = dr::mask_t<FloatD>;

    static matte::ffi::Param number_param(const std::string &name, double x) {
        return matte::ffi::Param{ rust::String(name), true, x, rust::String() };
    }
    static matte::ffi::Param text_param(const std::string &name, const std::string &s) {
        return matte::ffi::Param{ rust::String(name), false, 0.0, rust::String(s) };
    }

    void build_model() {
        try {
            m_model.emplace(matte::ffi::model_new(
                rust::Str(m_kind.data(), m_kind.size()),
                rust::Slice<const matte::ffi::Param>(m_params.data(), m_params.size())));
        } catch (const rust::Error &e) {
            Throw("bsdf \"%s\": %s", m_kind, e.what());
        }
        m_numeric.clear();
        for (const auto &p : (*m_model)->numeric_parameters())
            m_numeric.emplace_back(std::string(p.name), (ScalarFloat) p.number);
    }

    static matte::ffi::Vec3f to_ffi(const Vector3f &v) {
        if constexpr (!dr::is_jit_v<Float>)
            return matte::ffi::Vec3f{ (float) v.x(), (float) v.y(), (float) v.z() };
        else
            return matte::ffi::Vec3f{ 0.f, 0.f, 0.f };
    }

    void require_evaluated_mode(const char *method) const {
        if (jit_flag(JitFlag::SymbolicScope))
            Throw("bsdf \"%s\": %s() was called while Dr.Jit records a symbolic loop or call. "
                  "matte's kernels are Rust code, which cannot be traced into a Dr.Jit kernel, "
                  "so its llvm variants need evaluated mode: call "
                  "dr.set_flag(dr.JitFlag.SymbolicLoops, False) and "
                  "dr.set_flag(dr.JitFlag.SymbolicCalls, False) before rendering "
                  "(matte_mitsuba.evaluated_mode() does both; with the mitsuba tool: -W -W).",
                  m_kind, method);
    }

    /// The lane's channels as the plain struct the kernels take (no FFI call to build it).
    static matte::ffi::Channels to_channels(const UnpolarizedSpectrum &value) {
        matte::ffi::Channels c{};
        for (size_t k = 0; k < Channels; ++k)
            c.v[k] = (float) value[k];
        c.n = Channels;
        return c;
    }

    /// Flattens JIT floats and vectors into their scalar components (detached from AD).
    template <typename T> static void collect(const T &value, std::vector<FloatD> &out) {
        if constexpr (dr::depth_v<T> > 1) {
            for (size_t c = 0; c < dr::size_v<T>; ++c)
                collect(value.entry(c), out);
        } else {
            out.push_back(dr::detach<false>(value));
        }
    }

    /// The float components of `values`, detached and evaluated in one Dr.Jit launch: their
    /// buffers (width n, or width 1 for literals such as a uniform reflectance, which Rust
    /// broadcasts) are handed to Rust as they are, without copies.
    template <typename... Ts> static std::vector<FloatD> evaluated(const Ts &...values) {
        std::vector<FloatD> flat;
        (collect(values, flat), ...);
        for (FloatD &v : flat)
            dr::schedule(v);
        dr::eval();
        dr::sync_thread();
        return flat;
    }

    /// The mask as a byte buffer of width n or 1 (scheduled; evaluated with the inputs).
    static MaskD scheduled_mask(const Mask &active) {
        MaskD m = dr::detach<false>(active);
        dr::schedule(m);
        return m;
    }

    /// `count` uninitialised buffers of width `n` for Rust to fill.
    static std::vector<FloatD> allocated(size_t n, size_t count) {
        std::vector<FloatD> out(count);
        for (FloatD &v : out) {
            v = dr::empty<FloatD>(n);
            dr::schedule(v);
        }
        dr::eval();
        return out;
    }

    static rust::Slice<const float> view(const FloatD &v) {
        return rust::Slice<const float>(v.data(), dr::width(v));
    }
    static rust::Slice<float> view(FloatD &v, size_t n) { return rust::Slice<float>(v.data(), n); }

    /// Inputs: `wi` (3), then `directional` components (wo: 3, or the 2-D sample), then the
    /// reflectance channels.
    static matte::ffi::LanesIn lanes(const std::vector<FloatD> &in, size_t directional,
                                     const MaskD &mask) {
        static_assert(sizeof(bool) == 1, "Dr.Jit masks are handed over as bytes");
        auto at = [&](size_t k) { return k < in.size() ? view(in[k]) : rust::Slice<const float>(); };
        size_t rho = 3 + directional;
        return matte::ffi::LanesIn{ at(0), at(1), at(2), at(3), at(4),
                                    directional == 3 ? at(5) : rust::Slice<const float>(),
                                    Channels > 0 ? at(rho) : rust::Slice<const float>(),
                                    Channels > 1 ? at(rho + 1) : rust::Slice<const float>(),
                                    Channels > 2 ? at(rho + 2) : rust::Slice<const float>(),
                                    Channels > 3 ? at(rho + 3) : rust::Slice<const float>(),
                                    Channels,
                                    rust::Slice<const uint8_t>((const uint8_t *) mask.data(), dr::width(mask)) };
    }

    /// Outputs: the channels, the pdf, then (when present) wo.
    static matte::ffi::LanesOut lanes(std::vector<FloatD> &out, size_t n) {
        auto at = [&](size_t k) { return k < out.size() ? view(out[k], n) : rust::Slice<float>(); };
        auto channel = [&](size_t c) { return c < Channels ? at(c) : rust::Slice<float>(); };
        return matte::ffi::LanesOut{ channel(0), channel(1), channel(2), channel(3), at(Channels),
                                     at(Channels + 1), at(Channels + 2), at(Channels + 3) };
    }

    /// f·cos θo and the pdf: the kernels for every active lane, 0 elsewhere.
    std::pair<Spectrum, Float> eval_pdf_impl(const SurfaceInteraction3f &si, const Vector3f &wo,
                                             Mask active) const {
        Float cos_theta_i = Frame3f::cos_theta(si.wi), cos_theta_o = Frame3f::cos_theta(wo);
        active &= cos_theta_i > 0.f && cos_theta_o > 0.f;
        UnpolarizedSpectrum value = m_reflectance->eval(si, active);
        Float pdf;
        if constexpr (!dr::is_jit_v<Float>) {
            if (!active)
                return { 0.f, 0.f };
            matte::ffi::Channels f{};
            pdf = (*m_model)->eval_pdf(to_ffi(si.wi), to_ffi(wo), to_channels(value), f);
            for (size_t c = 0; c < Channels; ++c)
                value[c] = f.v[c] * cos_theta_o;
        } else {
            require_evaluated_mode("eval");
            size_t n = dr::width(si.wi, wo, value, active);
            MaskD mask = scheduled_mask(active);
            std::vector<FloatD> in = evaluated(si.wi, wo, value);
            std::vector<FloatD> out = allocated(n, Channels + 1);  // f, pdf
            matte::ffi::LanesIn lanes_in = lanes(in, 3, mask);  // wi, wo, reflectance
            matte::ffi::LanesOut lanes_out = lanes(out, n);
            (*m_model)->eval_pdf_lanes(lanes_in, lanes_out);
            for (size_t c = 0; c < Channels; ++c)
                value[c] = Float(out[c]) * cos_theta_o;
            pdf = dr::select(active, Float(out[Channels]), 0.f);
        }
        return { depolarizer<Spectrum>(value) & active, pdf };
    }

    std::string m_kind;
    ref<Texture> m_reflectance;
    std::vector<matte::ffi::Param> m_params;
    std::vector<std::pair<std::string, ScalarFloat>> m_numeric;
    /// Always set after construction (optional only because rust::Box has no empty state).
    std::optional<rust::Box<matte::ffi::Model>> m_model;

    MI_TRAVERSE_CB(Base, m_reflectance)
};

NAMESPACE_END(mitsuba)
