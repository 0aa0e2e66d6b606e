//! Embree 3 as a peer: `libembree3` loaded at run time (so building the
//! bench never needs it), single rays through `rtcIntersect1` and packets
//! of 16 through `rtcIntersect16`.
//!
//! The declarations below follow Debian's Embree 3.13 headers
//! (`/usr/include/embree3`), built with `RTC_MAX_INSTANCE_LEVEL_COUNT` 1 and
//! `RTC_MIN_WIDTH` 0, which fix the layout of `RTCIntersectContext`.

use glam::Vec3;
use libloading::Library;
use std::ffi::{c_char, c_void};
use std::time::{Duration, Instant};

type Handle = *mut c_void;

const RTC_GEOMETRY_TYPE_TRIANGLE: i32 = 0;
const RTC_BUFFER_TYPE_INDEX: i32 = 0;
const RTC_BUFFER_TYPE_VERTEX: i32 = 1;
const RTC_FORMAT_UINT3: i32 = 0x5003;
const RTC_FORMAT_FLOAT3: i32 = 0x9003;
const RTC_BUILD_QUALITY_MEDIUM: i32 = 1;
const RTC_DEVICE_PROPERTY_VERSION: i32 = 0;
const RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT: i32 = 0;
const RTC_INTERSECT_CONTEXT_FLAG_COHERENT: i32 = 1;
const RTC_INVALID_GEOMETRY_ID: u32 = u32::MAX;

#[repr(C, align(16))]
#[derive(Clone, Copy)]
struct RtcRay {
    org: [f32; 3],
    tnear: f32,
    dir: [f32; 3],
    time: f32,
    tfar: f32,
    mask: u32,
    id: u32,
    flags: u32,
}

#[repr(C, align(16))]
#[derive(Clone, Copy)]
struct RtcHit {
    ng: [f32; 3],
    u: f32,
    v: f32,
    prim_id: u32,
    geom_id: u32,
    inst_id: [u32; 1],
}

#[repr(C)]
#[derive(Clone, Copy)]
struct RtcRayHit {
    ray: RtcRay,
    hit: RtcHit,
}

/// `RTCRayHit16`: sixteen rays and hits, one array per field.
#[repr(C, align(64))]
#[derive(Clone, Copy)]
struct RtcRayHit16 {
    org: [[f32; 16]; 3],
    tnear: [f32; 16],
    dir: [[f32; 16]; 3],
    time: [f32; 16],
    tfar: [f32; 16],
    mask: [u32; 16],
    id: [u32; 16],
    flags: [u32; 16],
    ng: [[f32; 16]; 3],
    u: [f32; 16],
    v: [f32; 16],
    prim_id: [u32; 16],
    geom_id: [u32; 16],
    inst_id: [u32; 16],
}

const _: () = assert!(std::mem::size_of::<RtcRayHit16>() == 20 * 64);

/// `RTCIntersectContext` for `RTC_MAX_INSTANCE_LEVEL_COUNT` 1: no
/// `instStackSize`, no `minWidthDistanceFactor`.
#[repr(C)]
struct RtcIntersectContext {
    flags: i32,
    filter: Option<unsafe extern "C" fn(*const c_void)>,
    inst_id: [u32; 1],
}

impl RtcIntersectContext {
    /// `rtcInitIntersectContext`, an inline function in the C headers.
    fn new() -> Self {
        RtcIntersectContext {
            flags: RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT,
            filter: None,
            inst_id: [RTC_INVALID_GEOMETRY_ID],
        }
    }
}

const _: () = assert!(std::mem::size_of::<RtcRayHit>() == 80);
const _: () = assert!(std::mem::size_of::<RtcIntersectContext>() == 24);

/// The entry points the bench calls, copied out of the loaded library.
struct Api {
    new_device: unsafe extern "C" fn(*const c_char) -> Handle,
    release_device: unsafe extern "C" fn(Handle),
    get_device_error: unsafe extern "C" fn(Handle) -> i32,
    get_device_property: unsafe extern "C" fn(Handle, i32) -> isize,
    new_scene: unsafe extern "C" fn(Handle) -> Handle,
    release_scene: unsafe extern "C" fn(Handle),
    set_scene_build_quality: unsafe extern "C" fn(Handle, i32),
    commit_scene: unsafe extern "C" fn(Handle),
    new_geometry: unsafe extern "C" fn(Handle, i32) -> Handle,
    set_new_geometry_buffer: unsafe extern "C" fn(Handle, i32, u32, i32, usize, usize) -> *mut c_void,
    commit_geometry: unsafe extern "C" fn(Handle),
    attach_geometry: unsafe extern "C" fn(Handle, Handle) -> u32,
    release_geometry: unsafe extern "C" fn(Handle),
    intersect1: unsafe extern "C" fn(Handle, *mut RtcIntersectContext, *mut RtcRayHit),
    intersect16: unsafe extern "C" fn(*const i32, Handle, *mut RtcIntersectContext, *mut RtcRayHit16),
}

/// A loaded Embree and one device.
pub struct Embree {
    api: Api,
    device: Handle,
    pub version: String,
    pub library: String,
}

/// A committed scene of one triangle mesh.
pub struct Scene<'a> {
    embree: &'a Embree,
    scene: Handle,
}

// SAFETY: Embree documents `rtcIntersect1` on a committed scene as safe
// from any number of threads; the bench only intersects after the commit.
unsafe impl Sync for Scene<'_> {}
unsafe impl Send for Scene<'_> {}

const LIBRARIES: [&str; 2] = ["libembree3.so.3", "libembree3.so"];

/// Opens `$RT_EMBREE_LIB` when set, else Debian's libembree3.
fn open() -> Result<(Library, String), String> {
    let custom = std::env::var("RT_EMBREE_LIB").ok();
    let names: Vec<String> = match custom {
        Some(path) => vec![path],
        None => LIBRARIES.iter().map(|s| s.to_string()).collect(),
    };
    let mut why = Vec::new();
    for name in names {
        // SAFETY: loading Embree runs its (and TBB's) initialisers, which
        // have no preconditions.
        match unsafe { Library::new(&name) } {
            Ok(lib) => return Ok((lib, name)),
            Err(e) => why.push(e.to_string()),
        }
    }
    Err(why.join("; "))
}

fn is_root() -> bool {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| s.lines().find(|l| l.starts_with("Uid:")).map(|l| l.split_whitespace().nth(2) == Some("0")))
        .unwrap_or(false)
}

/// Installs Debian's Embree 3 runtime (what `bench/setup.sh` does).
fn install() -> Result<(), String> {
    let apt = |args: &[&str]| {
        std::process::Command::new("apt-get")
            .args(args)
            .env("DEBIAN_FRONTEND", "noninteractive")
            .stdout(std::process::Stdio::null())
            .status()
            .map_err(|e| format!("apt-get: {e}"))
            .and_then(|s| if s.success() { Ok(()) } else { Err(format!("apt-get {} failed ({s})", args.join(" "))) })
    };
    let get = ["install", "-y", "-qq", "libembree3-3"];
    apt(&get).or_else(|_| apt(&["update", "-qq"]).and_then(|_| apt(&get)))
}

impl Embree {
    /// Loads libembree3 and opens a device; with `may_install`, installs
    /// the Debian package first when the library is missing and we are root.
    pub fn load(may_install: bool) -> Result<Embree, String> {
        let (lib, name) = match open() {
            Ok(l) => l,
            Err(why) if may_install && is_root() => {
                eprintln!("embree: libembree3 not found ({why}); installing Debian's libembree3-3 (we are root)");
                install()?;
                open().map_err(|e| format!("installed libembree3-3 but still cannot load it: {e}"))?
            }
            Err(why) => {
                return Err(format!(
                    "libembree3 not found ({why}); run bench/setup.sh as root (apt-get install libembree-dev) to measure the Embree peer"
                ));
            }
        };
        // SAFETY: the signatures match Embree 3's C API (rtcore_*.h).
        let api = unsafe {
            macro_rules! sym {
                ($name:literal) => {
                    *lib.get($name).map_err(|e| format!("{name}: {e}"))?
                };
            }
            Api {
                new_device: sym!(b"rtcNewDevice\0"),
                release_device: sym!(b"rtcReleaseDevice\0"),
                get_device_error: sym!(b"rtcGetDeviceError\0"),
                get_device_property: sym!(b"rtcGetDeviceProperty\0"),
                new_scene: sym!(b"rtcNewScene\0"),
                release_scene: sym!(b"rtcReleaseScene\0"),
                set_scene_build_quality: sym!(b"rtcSetSceneBuildQuality\0"),
                commit_scene: sym!(b"rtcCommitScene\0"),
                new_geometry: sym!(b"rtcNewGeometry\0"),
                set_new_geometry_buffer: sym!(b"rtcSetNewGeometryBuffer\0"),
                commit_geometry: sym!(b"rtcCommitGeometry\0"),
                attach_geometry: sym!(b"rtcAttachGeometry\0"),
                release_geometry: sym!(b"rtcReleaseGeometry\0"),
                intersect1: sym!(b"rtcIntersect1\0"),
                intersect16: sym!(b"rtcIntersect16\0"),
            }
        };
        // Never unloaded: TBB's worker threads outlive the device, and
        // unmapping their code under them crashes the process at exit.
        std::mem::forget(lib);
        // SAFETY: a null configuration string asks for the defaults.
        let device = unsafe { (api.new_device)(std::ptr::null()) };
        if device.is_null() {
            return Err(format!("{name}: rtcNewDevice failed (unsupported CPU?)"));
        }
        // SAFETY: `device` is a live device.
        let v = unsafe { (api.get_device_property)(device, RTC_DEVICE_PROPERTY_VERSION) };
        let version = format!("{}.{}.{}", v / 10000, (v / 100) % 100, v % 100);
        if v / 10000 != 3 {
            // SAFETY: as above; released once.
            unsafe { (api.release_device)(device) };
            return Err(format!("{name} is Embree {version}; the bench declares Embree 3's API"));
        }
        Ok(Embree { api, device, version, library: name })
    }

    fn check(&self, what: &str) -> Result<(), String> {
        // SAFETY: `self.device` is live while `self` is.
        match unsafe { (self.api.get_device_error)(self.device) } {
            0 => Ok(()),
            e => Err(format!("embree: {what} failed with RTCError {e}")),
        }
    }

    /// Builds Embree's own BVH over the triangles (medium quality, its
    /// defaults otherwise); returns the scene and the time from the first
    /// call to the end of `rtcCommitScene` (vertex and index copies
    /// included).
    pub fn build(&self, positions: &[Vec3], indices: &[[u32; 3]]) -> Result<(Scene<'_>, Duration), String> {
        let a = &self.api;
        let t = Instant::now();
        // SAFETY: every handle comes from the call before it on a live
        // device; the buffers Embree returns hold `count` items of the
        // stride asked for, and we write exactly that many.
        unsafe {
            let scene = (a.new_scene)(self.device);
            if scene.is_null() {
                self.check("rtcNewScene")?;
                return Err("embree: rtcNewScene returned null".into());
            }
            let scene = Scene { embree: self, scene };
            (a.set_scene_build_quality)(scene.scene, RTC_BUILD_QUALITY_MEDIUM);
            let geom = (a.new_geometry)(self.device, RTC_GEOMETRY_TYPE_TRIANGLE);
            if geom.is_null() {
                self.check("rtcNewGeometry")?;
                return Err("embree: rtcNewGeometry returned null".into());
            }
            let vb =
                (a.set_new_geometry_buffer)(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 12, positions.len())
                    as *mut [f32; 3];
            let ib = (a.set_new_geometry_buffer)(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 12, indices.len())
                as *mut [u32; 3];
            if vb.is_null() || ib.is_null() {
                (a.release_geometry)(geom);
                self.check("rtcSetNewGeometryBuffer")?;
                return Err("embree: rtcSetNewGeometryBuffer returned null".into());
            }
            std::slice::from_raw_parts_mut(vb, positions.len())
                .iter_mut()
                .zip(positions)
                .for_each(|(d, p)| *d = p.to_array());
            std::slice::from_raw_parts_mut(ib, indices.len()).copy_from_slice(indices);
            (a.commit_geometry)(geom);
            (a.attach_geometry)(scene.scene, geom);
            (a.release_geometry)(geom);
            (a.commit_scene)(scene.scene);
            self.check("rtcCommitScene")?;
            Ok((scene, t.elapsed()))
        }
    }
}

impl Drop for Embree {
    fn drop(&mut self) {
        // SAFETY: every scene borrows `self`, so all are released by now.
        unsafe { (self.api.release_device)(self.device) };
    }
}

impl Scene<'_> {
    /// The closest hit of one ray: (distance, triangle index).
    #[inline]
    pub fn intersect(&self, o: Vec3, d: Vec3, tmin: f32) -> Option<(f32, u32)> {
        let mut ctx = RtcIntersectContext::new();
        let mut rh = RtcRayHit {
            ray: RtcRay {
                org: o.to_array(),
                tnear: tmin,
                dir: d.to_array(),
                time: 0.0,
                tfar: f32::INFINITY,
                mask: u32::MAX,
                id: 0,
                flags: 0,
            },
            hit: RtcHit {
                ng: [0.0; 3],
                u: 0.0,
                v: 0.0,
                prim_id: RTC_INVALID_GEOMETRY_ID,
                geom_id: RTC_INVALID_GEOMETRY_ID,
                inst_id: [RTC_INVALID_GEOMETRY_ID],
            },
        };
        // SAFETY: a committed scene, an initialised context and a 16-byte
        // aligned ray/hit.
        unsafe { (self.embree.api.intersect1)(self.scene, &mut ctx, &mut rh) };
        (rh.hit.geom_id != RTC_INVALID_GEOMETRY_ID).then_some((rh.ray.tfar, rh.hit.prim_id))
    }
}

/// Up to sixteen rays for [`Scene::intersect16`]: origin, direction, tmin.
pub type Rays16<'r> = &'r [(Vec3, Vec3, f32)];

impl Scene<'_> {
    /// The closest hits of up to sixteen rays in one `rtcIntersect16` call
    /// (`coherent`: the context's coherent flag, for primary rays), in
    /// `out` by ray.
    pub fn intersect16(&self, rays: Rays16, coherent: bool, out: &mut [Option<(f32, u32)>]) {
        assert!(rays.len() <= 16 && out.len() >= rays.len());
        let mut valid = [0i32; 16];
        // SAFETY: all-zero is a valid value of this plain-data struct.
        let mut rh: RtcRayHit16 = unsafe { std::mem::zeroed() };
        for (i, (o, d, tmin)) in rays.iter().enumerate() {
            valid[i] = -1;
            for k in 0..3 {
                rh.org[k][i] = o[k];
                rh.dir[k][i] = d[k];
            }
            rh.tnear[i] = *tmin;
            rh.tfar[i] = f32::INFINITY;
            rh.mask[i] = u32::MAX;
            rh.geom_id[i] = RTC_INVALID_GEOMETRY_ID;
            rh.prim_id[i] = RTC_INVALID_GEOMETRY_ID;
            rh.inst_id[i] = RTC_INVALID_GEOMETRY_ID;
        }
        let mut ctx = RtcIntersectContext::new();
        if coherent {
            ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
        }
        // SAFETY: a committed scene, an initialised context, a 64-byte
        // aligned packet and a valid mask of 16 ints.
        unsafe { (self.embree.api.intersect16)(valid.as_ptr(), self.scene, &mut ctx, &mut rh) };
        for (i, o) in out.iter_mut().enumerate().take(rays.len()) {
            *o = (rh.geom_id[i] != RTC_INVALID_GEOMETRY_ID).then_some((rh.tfar[i], rh.prim_id[i]));
        }
    }
}

impl Drop for Scene<'_> {
    fn drop(&mut self) {
        // SAFETY: created by `build`, released once.
        unsafe { (self.embree.api.release_scene)(self.scene) };
    }
}
