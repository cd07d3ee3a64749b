/*
 * matte's Mitsuba 3 BSDF: one class for every matte model, whose math is the Rust kernels
 * (rust/brdf/) called through the cxx bridge (rust/plugin/src/). Mitsuba loads the plugin under the
 * name of the `<bsdf type="...">` (one per registered model, `matte types`); that name selects
 * the model.
 *
 * Parameters (all optional): `reflectance` (spectrum or texture, default 0.5, evaluated per
 * channel) and the model's own, as its registry entry declares them (rust/brdf/<model>.rs;
 * `matte types --markdown`, the README's "Models and parameters"). The Rust parser validates
 * names and values, so this class knows no model's parameters.
 *
 * Every numeric parameter may also be a texture (`<texture type="bitmap" name="sigma">`):
 * evaluated with `eval_1` at the interaction, its kernel constants computed per lane inside
 * eval/sample/pdf (rust/brdf/src/lane.rs; docs/models.md#spatially-varying-parameters), traversed
 * as the texture (gradients reach its data). Constant parameters keep the per-value constants.
 *
 * `tabulated_brdf` is a registered type like the others: its parameter is a file (`filename`,
 * resolved by Mitsuba's file resolver; Rust reads and checks it, errors are one line naming the
 * file), its values one registered table the traced kernel gathers from, its interpolation in
 * the reflectance per lane and channel (differentiable), no numeric parameters.
 *
 * Every model is one-sided (use `twosided` for two-sided surfaces) and is sampled
 * cosine-weighted by default. `eval` returns f·cos θo as Mitsuba expects; the kernels return f.
 *
 * Variants: every variant of the wheel. Scalar variants call the f32 kernels per call. JIT
 * variants (llvm_ad_*, cuda_ad_*, rgb, mono, spectral and polarized) *trace* the same Rust
 * kernels: each operation becomes one Dr.Jit operation on the variant's `Float`, recorded
 * through the arena (cpp/arena_impl.h, rust/plugin/src/traced.rs). So the plugin works in symbolic
 * loops and calls (Dr.Jit's default mode, the `mitsuba` tool's default), on the CPU and the
 * GPU, and autodiff sees every operation: `reflectance` and the numeric parameters (sigma,
 * roughness, int_ior, ext_ior) are differentiable. The numeric parameters are opaque Dr.Jit
 * values, and the kernel constants derived from them are computed once per
 * `parameters_changed` (with their AD graph), so changing a value never recompiles a kernel.
 * Polarized variants are depolarizing, as Mitsuba's `diffuse`.
 */
#pragma once

#include <mitsuba/core/fresolver.h>
#include <mitsuba/core/properties.h>
#include <mitsuba/core/string.h>
#include <mitsuba/render/bsdf.h>
#include <mitsuba/render/texture.h>

#include "rust/cxx.h"  // rust::Error (the generated header declares only what it uses)
#include "matte/rust/plugin/src/bridge.rs.h"
#include "arena_impl.h"

#include <array>
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
        // Collect every other property and wrap the textures; the Rust construction
        // (matte_brdf::construction, the renderer's too) validates names and values and says
        // which parameters a texture may give. Anything else stays unqueried, so Mitsuba
        // reports it as an unreferenced property.
        std::vector<std::string> names;
        for (const auto &p : props)
            names.emplace_back(p.name());
        // The `<texture name="...">` children, in the order given.
        std::vector<std::pair<std::string, ref<Texture>>> textured;
        for (const std::string &name : names) {
            if (name == "reflectance")
                continue;
            switch (props.type(name)) {
                case Properties::Type::Object: {
                    // A texture for a numeric parameter (sigma, roughness, alpha, int_ior, ...):
                    // evaluated per lane (docs/models.md#spatially-varying-parameters); the model
                    // is built and validated with its mean.
                    ref<Texture> texture = props.get_unbounded_texture<Texture>(name);
                    m_params.push_back(param(name, matte::ffi::PropertyType::Texture, scalar_value(texture->mean())));
                    textured.emplace_back(name, texture);
                    break;
                }
                case Properties::Type::Float:
                case Properties::Type::Integer:
                    m_params.push_back(param(name, matte::ffi::PropertyType::Number, props.get<double>(name)));
                    break;
                case Properties::Type::String:
                    if (matte::ffi::is_file_parameter(rust::Str(m_kind.data(), m_kind.size()),
                                                      rust::Str(name.data(), name.size()))) {
                        // A file (tabulated_brdf's table): resolved as Mitsuba resolves files
                        // (next to the scene, then the search path); Rust reads it.
                        fs::path path = file_resolver()->resolve(props.get<std::string>(name));
                        m_params.push_back(param(name, matte::ffi::PropertyType::Text, 0.0, path.string()));
                    } else {
                        m_params.push_back(
                            param(name, matte::ffi::PropertyType::Text, 0.0, props.get<std::string>(name)));
                    }
                    break;
                case Properties::Type::Bool:
                    m_params.push_back(param(name, matte::ffi::PropertyType::Flag, props.get<bool>(name) ? 1.0 : 0.0));
                    break;
                default:
                    break;
            }
        }
        build_model();
        // The numeric parameters with their effective values (defaults filled in), as the
        // variant's Float: fixed from here on (traverse hands out references to them).
        for (const auto &p : (*m_model)->numeric_parameters()) {
            NumericParameter n{ text_of(p.name), Float((ScalarFloat) p.number), nullptr };
            for (auto &[name, texture] : textured)
                if (name == n.name)
                    n.texture = texture;
            m_numeric.push_back(std::move(n));
        }
        m_any_textured = !textured.empty();
        update_traced_kernel();
        m_flags = BSDFFlags::DiffuseReflection | BSDFFlags::FrontSide;
        m_components.push_back(m_flags);
    }

    void traverse(TraversalCallback *cb) override {
        cb->put("reflectance", m_reflectance, ParamFlags::Differentiable);
        for (NumericParameter &n : m_numeric) {
            if (n.texture)
                cb->put(n.name, n.texture, ParamFlags::Differentiable);
            else
                cb->put(n.name, n.value, ParamFlags::Differentiable);
        }
    }

    void parameters_changed(const std::vector<std::string> & /*keys*/ = {}) override {
        // Numeric parameters may have been edited through mi.traverse(): rebuild the model
        // with the new values (validated again by the kernels), then the traced constants.
        for (const NumericParameter &n : m_numeric) {
            if (n.texture)
                continue;  // evaluated per call
            double value = scalar_value(n.value);
            bool found = false;
            for (auto &p : m_params)
                if (text_of(p.name) == n.name) {
                    p.kind = matte::ffi::PropertyType::Number;
                    p.number = value;
                    found = true;
                }
            if (!found)
                m_params.push_back(param(n.name, matte::ffi::PropertyType::Number, value));
        }
        build_model();
        update_traced_kernel();
    }

    std::pair<BSDFSample3f, Spectrum> sample(const BSDFContext &ctx, const SurfaceInteraction3f &si,
                                             Float /* sample1 */, const Point2f &sample2, Mask active) const override {
        MI_MASKED_FUNCTION(ProfilerPhase::BSDFSample, active);
        Float cos_theta_i = Frame3f::cos_theta(si.wi);
        BSDFSample3f bs = dr::zeros<BSDFSample3f>();
        active &= cos_theta_i > 0.f;
        if (unlikely(dr::none_or<false>(active) || !ctx.is_enabled(BSDFFlags::DiffuseReflection)))
            return { bs, 0.f };

        UnpolarizedSpectrum value = m_reflectance->eval(si, active);
        if constexpr (!dr::is_jit_v<Float>) {
            matte::ffi::Channels weight{};
            matte::ffi::Vec3f wo{ 0.f, 0.f, 1.f };
            auto params = lane_values(si, active);
            float pdf = (*m_model)->sample(rust::Slice<const float>(params.data(), params.size()), to_ffi(si.wi),
                                           (float) sample2.x(), (float) sample2.y(), to_channels(value), wo, weight);
            bs.wo = Vector3f(wo.x, wo.y, wo.z);
            bs.pdf = pdf;
            for (size_t c = 0; c < Channels; ++c)
                value[c] = weight.v[c];
        } else {
            matte::ArenaT<Float> ar(&m_tables);
            auto wi = ids(ar, si.wi);
            auto rho = ids(ar, value);
            auto coef = coefficient_ids(ar, si, active);
            uint32_t zero = ar.lit(0.f);
            std::array<uint32_t, 3> wo;
            std::array<uint32_t, Channels> weight;
            wo.fill(zero);
            weight.fill(zero);
            uint32_t pdf =
                (*m_model)->traced_sample(ar, slice(coef), m_any_textured, slice(wi), ar.push(sample2.x()),
                                          ar.push(sample2.y()), slice(rho), mut_slice(wo), mut_slice(weight));
            // Zero on inactive lanes: their parameters (textures evaluated under `active`) are
            // not the material's, so neither is what the sampler drew there.
            bs.wo = dr::select(active, Vector3f(ar.get(wo[0]), ar.get(wo[1]), ar.get(wo[2])), 0.f);
            // Detached: a sampling density (see eval_pdf_impl).
            bs.pdf = dr::select(active, dr::detach(ar.get(pdf)), 0.f);
            for (size_t c = 0; c < Channels; ++c)
                value[c] = ar.get(weight[c]);
        }
        bs.eta = 1.f;
        bs.sampled_type = +BSDFFlags::DiffuseReflection;
        bs.sampled_component = 0;
        return { bs, depolarizer<Spectrum>(value) & (active && bs.pdf > 0.f) };
    }

    Spectrum eval(const BSDFContext &ctx, const SurfaceInteraction3f &si, const Vector3f &wo,
                  Mask active) const override {
        MI_MASKED_FUNCTION(ProfilerPhase::BSDFEvaluate, active);
        if (!ctx.is_enabled(BSDFFlags::DiffuseReflection))
            return 0.f;
        return eval_pdf_impl(si, wo, active).first;
    }

    Float pdf(const BSDFContext &ctx, const SurfaceInteraction3f &si, const Vector3f &wo, Mask active) const override {
        MI_MASKED_FUNCTION(ProfilerPhase::BSDFEvaluate, active);
        if (!ctx.is_enabled(BSDFFlags::DiffuseReflection))
            return 0.f;
        if constexpr (!dr::is_jit_v<Float>) {
            if (!(active && Frame3f::cos_theta(si.wi) > 0.f && Frame3f::cos_theta(wo) > 0.f))
                return 0.f;
            auto params = lane_values(si, active);
            return (*m_model)->pdf(rust::Slice<const float>(params.data(), params.size()), to_ffi(si.wi), to_ffi(wo));
        } else {
            // Dr.Jit records only what the pdf depends on: the value's operations are dropped.
            return eval_pdf_impl(si, wo, active).second;
        }
    }

    std::pair<Spectrum, Float> eval_pdf(const BSDFContext &ctx, const SurfaceInteraction3f &si, const Vector3f &wo,
                                        Mask active) const override {
        MI_MASKED_FUNCTION(ProfilerPhase::BSDFEvaluate, active);
        if (!ctx.is_enabled(BSDFFlags::DiffuseReflection))
            return { 0.f, 0.f };
        return eval_pdf_impl(si, wo, active);
    }

    Spectrum eval_diffuse_reflectance(const SurfaceInteraction3f &si, Mask active) const override {
        return m_reflectance->eval(si, active);
    }

    std::string to_string() const override {
        std::ostringstream oss;
        oss << "MatteBSDF[" << std::endl
            << "  type = \"" << m_kind << "\"," << std::endl
            << "  reflectance = " << string::indent(m_reflectance) << "," << std::endl;
        for (const auto &p : (*m_model)->describe_parameters()) {
            oss << "  " << text_of(p.name) << " = ";
            const Texture *tex = nullptr;
            for (const NumericParameter &n : m_numeric)
                if (n.name == text_of(p.name) && n.texture)
                    tex = n.texture.get();
            if (tex)
                oss << string::indent(tex);
            else if (p.kind == matte::ffi::PropertyType::Number)
                oss << p.number;
            else
                oss << "\"" << text_of(p.text) << "\"";
            oss << "," << std::endl;
        }
        oss << "]";
        return oss.str();
    }

    MI_DECLARE_CLASS(MatteBSDF)

private:
    static constexpr size_t Channels = dr::size_v<UnpolarizedSpectrum>;

    static matte::ffi::Param param(const std::string &name, matte::ffi::PropertyType kind, double number,
                                   const std::string &text = {}) {
        return matte::ffi::Param{ rust::String(name.data(), name.size()), kind, number,
                                  rust::String(text.data(), text.size()) };
    }
    /// Strings cross the bridge as pointer and length only: cxx's own std::string conversions are
    /// compiled into the kernels library (lib/libmatte_kernels.so) with one C++ string ABI, and
    /// the layers of Mitsuba 3.7.x use the other (cpp/build_plugin.sh).
    static std::string text_of(const rust::String &s) { return std::string(s.data(), s.size()); }

    void build_model() {
        try {
            m_model.emplace(
                matte::ffi::bsdf_new(rust::Str(m_kind.data(), m_kind.size()),
                                     rust::Slice<const matte::ffi::Param>(m_params.data(), m_params.size())));
        } catch (const rust::Error &e) {
            Throw("bsdf \"%s\": %s", m_kind, e.what());
        }
    }

    /// The value of a (width-1) parameter, detached from autodiff.
    static double scalar_value(const Float &v) {
        if constexpr (dr::is_jit_v<Float>)
            return (double) dr::slice(dr::detach(v), 0);
        else
            return (double) v;
    }

    /// JIT variants: the tables (uploaded once per parameter value) and the kernel constants,
    /// computed by the traced Rust code from the parameters, with their AD graph when a
    /// parameter carries a gradient. Parameters and constants are opaque: new values never
    /// recompile a kernel.
    void update_traced_kernel() {
        if constexpr (dr::is_jit_v<Float>) {
            // Textured parameters read the per-lane tables (van Ginneken's stacks over m),
            // uploaded once: they do not depend on the parameter values.
            if (!m_any_textured || m_tables.empty()) {
                m_tables.clear();
                for (size_t k = 0; k < (*m_model)->table_count(m_any_textured); ++k) {
                    rust::Slice<const float> t = (*m_model)->table(k, m_any_textured);
                    m_tables.push_back(dr::load<Float>(t.data(), t.size()));
                }
            }
            bool differentiable = false;
            for (NumericParameter &n : m_numeric) {
                dr::make_opaque(n.value);
                differentiable |= dr::grad_enabled(n.value);
            }
            matte::ArenaT<Float> ar;
            std::vector<uint32_t> params;
            for (const NumericParameter &n : m_numeric)
                params.push_back(ar.push(n.value));
            rust::Vec<uint32_t> coef = (*m_model)->traced_coefficients(
                ar, rust::Slice<const uint32_t>(params.data(), params.size()), false, differentiable);
            m_coefficients.clear();
            for (uint32_t id : coef)
                m_coefficients.push_back(ar.get(id));
            for (Float &c : m_coefficients)
                dr::make_opaque(c);
        }
    }

    static matte::ffi::Vec3f to_ffi(const Vector3f &v) {
        if constexpr (!dr::is_jit_v<Float>)
            return matte::ffi::Vec3f{ (float) v.x(), (float) v.y(), (float) v.z() };
        else
            return matte::ffi::Vec3f{ 0.f, 0.f, 0.f };
    }

    /// The lane's channels as the plain struct the kernels take (no FFI call to build it).
    static matte::ffi::Channels to_channels(const UnpolarizedSpectrum &value) {
        matte::ffi::Channels c{};
        if constexpr (!dr::is_jit_v<Float>) {
            for (size_t k = 0; k < Channels; ++k)
                c.v[k] = (float) value[k];
        }
        c.n = Channels;
        return c;
    }

    /// Puts the components of a JIT vector (or the entries of a list) into the arena.
    template <typename Vec>
    static auto ids(const matte::ArenaT<Float> &ar, const Vec &v) {
        if constexpr (std::is_same_v<Vec, std::vector<Float>>) {
            std::vector<uint32_t> out;
            for (const Float &x : v)
                out.push_back(ar.push(x));
            return out;
        } else {
            std::array<uint32_t, dr::size_v<Vec>> out;
            for (size_t c = 0; c < dr::size_v<Vec>; ++c)
                out[c] = ar.push(v[c]);
            return out;
        }
    }
    template <typename C>
    static rust::Slice<const uint32_t> slice(const C &c) {
        return rust::Slice<const uint32_t>(c.data(), c.size());
    }
    template <typename C>
    static rust::Slice<uint32_t> mut_slice(C &c) {
        return rust::Slice<uint32_t>(c.data(), c.size());
    }

    /// Scalar variants: the numeric parameters' values at this hit (textures evaluated), or
    /// none when no parameter is textured (the model's constants are used).
    std::vector<float> lane_values(const SurfaceInteraction3f &si, Mask active) const {
        std::vector<float> out;
        if constexpr (!dr::is_jit_v<Float>) {
            if (m_any_textured)
                for (const NumericParameter &n : m_numeric)
                    out.push_back(n.texture ? (float) n.texture->eval_1(si, active) : (float) n.value);
        }
        return out;
    }

    /// JIT variants: the kernel constants in the arena. Constant parameters: the ones
    /// computed in `parameters_changed`. Textured ones: computed here per lane from the
    /// textures' values at `si` (traced, so gradients reach the texture's data).
    std::vector<uint32_t> coefficient_ids(const matte::ArenaT<Float> &ar, const SurfaceInteraction3f &si,
                                          Mask active) const {
        if (!m_any_textured)
            return ids(ar, m_coefficients);
        std::vector<uint32_t> params;
        for (const NumericParameter &n : m_numeric)
            params.push_back(ar.push(n.texture ? n.texture->eval_1(si, active) : n.value));
        rust::Vec<uint32_t> coef =
            (*m_model)->traced_coefficients(ar, rust::Slice<const uint32_t>(params.data(), params.size()), true, true);
        return std::vector<uint32_t>(coef.begin(), coef.end());
    }

    /// f·cos θo and the pdf: the kernels for every active lane, 0 elsewhere.
    std::pair<Spectrum, Float> eval_pdf_impl(const SurfaceInteraction3f &si, const Vector3f &wo, Mask active) const {
        Float cos_theta_i = Frame3f::cos_theta(si.wi), cos_theta_o = Frame3f::cos_theta(wo);
        active &= cos_theta_i > 0.f && cos_theta_o > 0.f;
        if constexpr (!dr::is_jit_v<Float>) {
            if (!active)
                return { 0.f, 0.f };
        }
        UnpolarizedSpectrum value = m_reflectance->eval(si, active);
        Float pdf;
        if constexpr (!dr::is_jit_v<Float>) {
            matte::ffi::Channels f{};
            auto params = lane_values(si, active);
            pdf = (*m_model)->eval_pdf(rust::Slice<const float>(params.data(), params.size()), to_ffi(si.wi),
                                       to_ffi(wo), to_channels(value), f);
            for (size_t c = 0; c < Channels; ++c)
                value[c] = f.v[c] * cos_theta_o;
        } else {
            matte::ArenaT<Float> ar(&m_tables);
            auto wi_ = ids(ar, si.wi), wo_ = ids(ar, wo);
            auto rho = ids(ar, value);
            auto coef = coefficient_ids(ar, si, active);
            std::array<uint32_t, Channels> v;
            v.fill(ar.lit(0.f));
            uint32_t pdf_id = (*m_model)->traced_eval_pdf(ar, slice(coef), m_any_textured, slice(wi_), slice(wo_),
                                                          slice(rho), mut_slice(v));
            for (size_t c = 0; c < Channels; ++c)
                value[c] = ar.get(v[c]);
            // The pdf is a sampling density: detached, so that prb's emitter-sampling MIS weight
            // (differentiated, while the BSDF-sampling one is not) adds no gradient of its own
            // where the sampler depends on a parameter (docs/sampling.md#gradients).
            pdf = dr::detach(ar.get(pdf_id));
        }
        return { depolarizer<Spectrum>(value) & active, dr::select(active, pdf, 0.f) };
    }

    std::string m_kind;
    ref<Texture> m_reflectance;
    std::vector<matte::ffi::Param> m_params;

    /// One numeric parameter, in the model's order: its name, its value (traversed when no
    /// texture gives it) and its texture, if one was given.
    struct NumericParameter {
        std::string name;
        Float value;
        ref<Texture> texture;

        // Dr.Jit's traversal of the JIT state (MI_TRAVERSE_CB, frozen functions): the texture.
        void traverse_1_cb_ro(void *payload, drjit::detail::traverse_callback_ro fn) const {
            drjit::traverse_1_fn_ro(texture, payload, fn);
        }
        void traverse_1_cb_rw(void *payload, drjit::detail::traverse_callback_rw fn) {
            drjit::traverse_1_fn_rw(texture, payload, fn);
        }
    };
    std::vector<NumericParameter> m_numeric;
    /// Whether any numeric parameter is textured (then every evaluation is per lane).
    bool m_any_textured = false;
    /// JIT variants: the kernel's constants and tables (`update_traced_kernel`).
    std::vector<Float> m_coefficients;
    std::vector<Float> m_tables;
    /// Always set after construction (optional only because rust::Box has no empty state).
    std::optional<rust::Box<matte::ffi::PluginBsdf>> m_model;

    MI_TRAVERSE_CB(Base, m_reflectance, m_numeric)
};

NAMESPACE_END(mitsuba)
