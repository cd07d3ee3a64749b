//! The few Embree 3 calls the renderer needs, loaded at run time with `libloading`: Embree
//! 3.13's shared library as each platform names it ([`library_name`]): `libembree3.so.3` on
//! Linux (Debian 12's `libembree3-3`) and other Unix, `libembree3.dylib` on macOS (Homebrew's
//! `embree@3`; Mitsuba's macOS wheel ships `mitsuba/libembree3.dylib`), `embree3.dll` on
//! Windows (Embree's release archive). The platform's loader looks the name up as usual:
//! `LD_LIBRARY_PATH` and the system folders on Linux, `DYLD_LIBRARY_PATH` and
//! `DYLD_FALLBACK_LIBRARY_PATH` on macOS, the executable's folder and `PATH` on Windows.
//!
//! Why a hand-written FFI and not a binding crate: the Rust bindings for Embree 3 on crates.io
//! (`embree` 0.3, `embree3-sys` 0.1) are unmaintained and link `-lembree3` at build time. A
//! link-time dependency would make every build of matte fail on a machine without Embree, and
//! would put `rtc*` references into the crate's staticlib, which the Mitsuba plugin links into
//! a process whose `libmitsuba` carries its own Embree. Loading the library at run time (on
//! Unix with `RTLD_NOW | RTLD_LOCAL`; a Windows DLL's exports are only ever reached through its
//! handle) and looking the functions up by handle keeps both apart: a build never needs
//! Embree, a machine without it renders with the CWBVH (`super::cwbvh`), and the symbols can
//! never bind to another Embree. The declarations mirror `embree3/rtcore_*.h` of 3.13.5
//! (`RTC_MAX_INSTANCE_LEVEL_COUNT` = 1, `RTC_MIN_WIDTH` = 0), and only what is used here.

use std::error::Error as _;
use std::ffi::{CStr, c_char, c_int, c_uint, c_void};
use std::sync::OnceLock;

pub type RTCDevice = *mut c_void;
pub type RTCScene = *mut c_void;
pub type RTCGeometry = *mut c_void;

/// `RTC_GEOMETRY_TYPE_TRIANGLE`.
pub const GEOMETRY_TYPE_TRIANGLE: c_int = 0;
/// `RTC_GEOMETRY_TYPE_USER`.
pub const GEOMETRY_TYPE_USER: c_int = 120;
/// `RTC_BUFFER_TYPE_INDEX`, `RTC_BUFFER_TYPE_VERTEX`.
pub const BUFFER_TYPE_INDEX: c_int = 0;
pub const BUFFER_TYPE_VERTEX: c_int = 1;
/// `RTC_FORMAT_UINT3`, `RTC_FORMAT_FLOAT3`.
pub const FORMAT_UINT3: c_int = 0x5003;
pub const FORMAT_FLOAT3: c_int = 0x9003;
/// `RTC_BUILD_QUALITY_HIGH` (what Mitsuba 3 sets, `src/render/scene_embree.inl`).
pub const BUILD_QUALITY_HIGH: c_int = 2;
/// `RTC_SCENE_FLAG_NONE` (Mitsuba's default: `embree_use_robust_intersections` = false).
pub const SCENE_FLAG_NONE: c_int = 0;
/// `RTC_INVALID_GEOMETRY_ID`.
pub const INVALID_GEOMETRY_ID: c_uint = u32::MAX;
/// `RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT`, `RTC_INTERSECT_CONTEXT_FLAG_COHERENT`.
pub const CONTEXT_FLAG_INCOHERENT: c_int = 0;

/// `struct RTCRay` (16-byte aligned, 48 bytes).
#[repr(C, align(16))]
#[derive(Clone, Copy, Debug, Default)]
pub struct RtcRay {
    pub org: [f32; 3],
    pub tnear: f32,
    pub dir: [f32; 3],
    pub time: f32,
    pub tfar: f32,
    pub mask: c_uint,
    pub id: c_uint,
    pub flags: c_uint,
}

/// `struct RTCHit` (16-byte aligned, 32 bytes).
#[repr(C, align(16))]
#[derive(Clone, Copy, Debug, Default)]
pub struct RtcHit {
    pub ng: [f32; 3],
    pub u: f32,
    pub v: f32,
    pub prim_id: c_uint,
    pub geom_id: c_uint,
    pub inst_id: [c_uint; 1],
}

/// `struct RTCRayHit`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default)]
pub struct RtcRayHit {
    pub ray: RtcRay,
    pub hit: RtcHit,
}

/// `struct RTCRayHit8`: eight rays and hits in structure-of-arrays layout, field `k` (the
/// order of [`UserQueryArgs`]) of lane `i` at `f[k][i]`.
#[repr(C, align(32))]
#[derive(Clone, Copy, Debug)]
pub struct RtcRayHit8 {
    pub f: [[f32; 8]; 20],
}

/// The `valid` mask of `rtcIntersect8` / `rtcOccluded8`: one `int` per lane, -1 = trace, 0 =
/// skip. Embree loads it as one 32-byte vector and requires 32-byte alignment (a plain
/// `[c_int; 8]` is 4-byte aligned, and the aligned load faults when it lands elsewhere).
#[repr(C, align(32))]
#[derive(Clone, Copy, Debug)]
pub struct ValidMask8(pub [c_int; 8]);

// The packet structures' alignment is part of Embree's ABI: checked when compiling.
const _: () = assert!(align_of::<ValidMask8>() == 32 && align_of::<RtcRayHit8>() == 32 && align_of::<RtcRay8>() == 32);

/// `struct RTCRay8`: eight rays in structure-of-arrays layout (the first 12 fields of
/// [`RtcRayHit8`]).
#[repr(C, align(32))]
#[derive(Clone, Copy, Debug)]
pub struct RtcRay8 {
    pub f: [[f32; 8]; 12],
}

/// `struct RTCIntersectContext` as `rtcInitIntersectContext` fills it.
#[repr(C)]
pub struct IntersectContext {
    pub flags: c_int,
    pub filter: *const c_void,
    pub inst_id: [c_uint; 1],
}

impl IntersectContext {
    /// `rtcInitIntersectContext`: incoherent rays, no filter, no instance.
    #[inline(always)]
    pub fn incoherent() -> Self {
        IntersectContext { flags: CONTEXT_FLAG_INCOHERENT, filter: std::ptr::null(), inst_id: [INVALID_GEOMETRY_ID] }
    }
}

/// `struct RTCBounds`.
#[repr(C, align(16))]
#[derive(Clone, Copy, Debug, Default)]
pub struct RtcBounds {
    pub lower: [f32; 3],
    pub align0: f32,
    pub upper: [f32; 3],
    pub align1: f32,
}

/// `struct RTCBoundsFunctionArguments`.
#[repr(C)]
pub struct BoundsArgs {
    pub geometry_user_ptr: *mut c_void,
    pub prim_id: c_uint,
    pub time_step: c_uint,
    pub bounds_o: *mut RtcBounds,
}

/// `struct RTCIntersectFunctionNArguments` and `struct RTCOccludedFunctionNArguments` (the
/// same layout): `N` rays in structure-of-arrays layout at `rayhit` (float `k` of ray `i` at
/// `k·N + i`: origin 0–2, tnear 3, direction 4–6, time 7, tfar 8, mask, id, flags; then, for
/// intersect only, Ng 12–14, u 15, v 16, primID 17, geomID 18, instID 19).
#[repr(C)]
pub struct UserQueryArgs {
    pub valid: *const c_int,
    pub geometry_user_ptr: *mut c_void,
    pub prim_id: c_uint,
    pub context: *mut IntersectContext,
    pub rayhit: *mut f32,
    pub n: c_uint,
    pub geom_id: c_uint,
}

pub type BoundsFn = unsafe extern "C" fn(*const BoundsArgs);
pub type UserQueryFn = unsafe extern "C" fn(*const UserQueryArgs);

/// The resolved entry points (names as in `rtcore_*.h`).
pub struct Api {
    pub new_device: unsafe extern "C" fn(*const c_char) -> RTCDevice,
    pub get_device_error: unsafe extern "C" fn(RTCDevice) -> c_int,
    pub new_scene: unsafe extern "C" fn(RTCDevice) -> RTCScene,
    pub release_scene: unsafe extern "C" fn(RTCScene),
    pub set_scene_build_quality: unsafe extern "C" fn(RTCScene, c_int),
    pub set_scene_flags: unsafe extern "C" fn(RTCScene, c_int),
    pub commit_scene: unsafe extern "C" fn(RTCScene),
    pub new_geometry: unsafe extern "C" fn(RTCDevice, c_int) -> RTCGeometry,
    pub set_new_geometry_buffer: unsafe extern "C" fn(RTCGeometry, c_int, c_uint, c_int, usize, usize) -> *mut c_void,
    pub commit_geometry: unsafe extern "C" fn(RTCGeometry),
    pub attach_geometry: unsafe extern "C" fn(RTCScene, RTCGeometry) -> c_uint,
    pub release_geometry: unsafe extern "C" fn(RTCGeometry),
    pub set_geometry_user_primitive_count: unsafe extern "C" fn(RTCGeometry, c_uint),
    pub set_geometry_user_data: unsafe extern "C" fn(RTCGeometry, *mut c_void),
    pub set_geometry_bounds_function: unsafe extern "C" fn(RTCGeometry, BoundsFn, *mut c_void),
    pub set_geometry_intersect_function: unsafe extern "C" fn(RTCGeometry, UserQueryFn),
    pub set_geometry_occluded_function: unsafe extern "C" fn(RTCGeometry, UserQueryFn),
    pub intersect1: unsafe extern "C" fn(RTCScene, *mut IntersectContext, *mut RtcRayHit),
    pub occluded1: unsafe extern "C" fn(RTCScene, *mut IntersectContext, *mut RtcRay),
    pub intersect8: unsafe extern "C" fn(*const ValidMask8, RTCScene, *mut IntersectContext, *mut RtcRayHit8),
    pub occluded8: unsafe extern "C" fn(*const ValidMask8, RTCScene, *mut IntersectContext, *mut RtcRay8),
    /// One device for the process (Embree's thread pool is per device); never released.
    pub device: RTCDevice,
    /// The loaded library, which the entry points above live in: kept as long as they are
    /// (the process, [`api`]'s `static`).
    _library: libloading::Library,
}

// SAFETY: the device handle is only used to create scenes and geometries, which Embree allows
// from any thread; the function pointers are plain code addresses.
unsafe impl Send for Api {}
unsafe impl Sync for Api {}

/// The shared library's file name on the platform `os` (as [`std::env::consts::OS`] names it).
pub fn library_name(os: &str) -> &'static str {
    match os {
        "macos" => "libembree3.dylib",
        "windows" => "embree3.dll",
        // Linux (Debian's `libembree3-3`) and the other Unix systems: the ELF soname.
        _ => "libembree3.so.3",
    }
}

/// The shared library's file name on this platform ([`library_name`]).
pub fn library() -> &'static str {
    library_name(std::env::consts::OS)
}

static API: OnceLock<Result<Api, String>> = OnceLock::new();

/// Embree, loaded once per process, or why it could not be loaded.
pub fn api() -> Result<&'static Api, &'static str> {
    API.get_or_init(load).as_ref().map_err(String::as_str)
}

/// Opens `name` with the platform's loader: on Unix `dlopen(name, RTLD_NOW | RTLD_LOCAL)`,
/// which keeps its symbols out of the global scope; on Windows `LoadLibraryExW`.
fn open(name: &str) -> Result<libloading::Library, libloading::Error> {
    #[cfg(unix)]
    {
        use libloading::os::unix::{Library, RTLD_LOCAL, RTLD_NOW};
        // SAFETY: loading Embree runs only its initialisers (no requirements on the caller);
        // it is never unloaded once its device exists (the library lives in `API`).
        unsafe { Library::open(Some(name), RTLD_NOW | RTLD_LOCAL) }.map(Into::into)
    }
    #[cfg(not(unix))]
    {
        // SAFETY: as above.
        unsafe { libloading::Library::new(name) }
    }
}

/// Why the loader failed: the system's own message (`dlerror`, or the Windows error) where it
/// gave one.
fn reason(e: &libloading::Error) -> String {
    e.source().map_or_else(|| e.to_string(), ToString::to_string)
}

fn load() -> Result<Api, String> {
    let name = library();
    let library = open(name).map_err(|e| format!("cannot load {name} ({})", reason(&e)))?;
    let sym = |s: &CStr| -> Result<*mut c_void, String> {
        // SAFETY: the symbol is only read as an address here (its type is `F` in `fn_pointer`).
        let p = unsafe { library.get::<*mut c_void>(s) }
            .map(|p| *p)
            .map_err(|e| format!("{name} has no symbol {} ({})", s.to_string_lossy(), reason(&e)))?;
        if p.is_null() { Err(format!("{name} has no symbol {}", s.to_string_lossy())) } else { Ok(p) }
    };
    macro_rules! f {
        ($name:literal) => {
            // SAFETY: the symbol is the Embree 3 function of that name, whose C signature is
            // the field's type (rtcore_*.h of Embree 3.13).
            unsafe { fn_pointer(sym($name)?) }
        };
    }
    // Every entry point first, so that no device is made in a library that is then unloaded.
    let mut api = Api {
        new_device: f!(c"rtcNewDevice"),
        get_device_error: f!(c"rtcGetDeviceError"),
        new_scene: f!(c"rtcNewScene"),
        release_scene: f!(c"rtcReleaseScene"),
        set_scene_build_quality: f!(c"rtcSetSceneBuildQuality"),
        set_scene_flags: f!(c"rtcSetSceneFlags"),
        commit_scene: f!(c"rtcCommitScene"),
        new_geometry: f!(c"rtcNewGeometry"),
        set_new_geometry_buffer: f!(c"rtcSetNewGeometryBuffer"),
        commit_geometry: f!(c"rtcCommitGeometry"),
        attach_geometry: f!(c"rtcAttachGeometry"),
        release_geometry: f!(c"rtcReleaseGeometry"),
        set_geometry_user_primitive_count: f!(c"rtcSetGeometryUserPrimitiveCount"),
        set_geometry_user_data: f!(c"rtcSetGeometryUserData"),
        set_geometry_bounds_function: f!(c"rtcSetGeometryBoundsFunction"),
        set_geometry_intersect_function: f!(c"rtcSetGeometryIntersectFunction"),
        set_geometry_occluded_function: f!(c"rtcSetGeometryOccludedFunction"),
        intersect1: f!(c"rtcIntersect1"),
        occluded1: f!(c"rtcOccluded1"),
        intersect8: f!(c"rtcIntersect8"),
        occluded8: f!(c"rtcOccluded8"),
        device: std::ptr::null_mut(),
        _library: library,
    };
    // SAFETY: a null config string selects Embree's defaults.
    api.device = unsafe { (api.new_device)(std::ptr::null()) };
    if api.device.is_null() {
        // Embree may have started threads before it failed: the library stays loaded.
        std::mem::forget(api);
        return Err(format!("{name}: rtcNewDevice failed (is the CPU supported?)"));
    }
    Ok(api)
}

/// The function pointer of type `F` at `p`.
///
/// # Safety
/// `p` must be the address of a function whose C signature is `F`.
unsafe fn fn_pointer<F: Copy>(p: *mut c_void) -> F {
    const { assert!(std::mem::size_of::<F>() == std::mem::size_of::<*mut c_void>()) };
    // SAFETY: same size (checked above); the caller guarantees the signature.
    unsafe { std::mem::transmute_copy::<*mut c_void, F>(&p) }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The layouts `rtcore_ray.h` and `rtcore_common.h` define (sizes from the C headers).
    #[test]
    fn layouts_match_the_c_headers() {
        assert_eq!(std::mem::size_of::<RtcRay>(), 48);
        assert_eq!(std::mem::size_of::<RtcHit>(), 32);
        assert_eq!(std::mem::size_of::<RtcRayHit>(), 80);
        assert_eq!(std::mem::align_of::<RtcRayHit>(), 16);
        assert_eq!(std::mem::size_of::<IntersectContext>(), 24);
        assert_eq!(std::mem::size_of::<RtcBounds>(), 32);
        assert_eq!(std::mem::size_of::<RtcRayHit8>(), 640);
        assert_eq!(std::mem::size_of::<RtcRay8>(), 384);
        assert_eq!(std::mem::align_of::<RtcRay8>(), 32);
        assert_eq!(std::mem::size_of::<BoundsArgs>(), 24);
        assert_eq!(std::mem::size_of::<UserQueryArgs>(), 48);
    }

    /// Each platform's file name for Embree 3, whichever platform runs the test.
    #[test]
    fn the_library_is_named_as_each_platform_ships_it() {
        assert_eq!(library_name("linux"), "libembree3.so.3");
        assert_eq!(library_name("freebsd"), "libembree3.so.3");
        assert_eq!(library_name("macos"), "libembree3.dylib");
        assert_eq!(library_name("windows"), "embree3.dll");
        assert_eq!(library(), library_name(std::env::consts::OS));
        if cfg!(target_os = "linux") {
            assert_eq!(library(), "libembree3.so.3");
        }
    }

    /// Without the library (a name no system has), the loader's reason is one line (on Linux,
    /// `dlerror`'s, which names the file).
    #[test]
    fn a_missing_library_is_reported_with_the_loaders_reason() {
        let e = open("libmatte_no_such_library.so.0").map(|_| ()).unwrap_err();
        let why = reason(&e);
        assert!(!why.is_empty() && !why.contains('\n'), "{why}");
        if cfg!(target_os = "linux") {
            assert!(why.contains("libmatte_no_such_library.so.0"), "{why}");
        }
    }
}
