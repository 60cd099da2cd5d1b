//! Intel Embree 3 (the system's `libembree3`; 3.13 on Debian) through the `embree` crate
//! 0.3.8, behind the bench crate's `embree` feature. Embree picks its SSE/AVX2/AVX-512 kernels
//! at run time, whatever the Rust side is compiled with.
//!
//! Everything goes through the crate's `sys` bindings: its safe `Device::new` passes Embree no
//! configuration and keeps its handle private, so a device that builds on one thread
//! (`threads=1`) can only be made there, and the memory monitor and `rtcPointQuery` are only
//! there. The bindings were generated from Embree 3.12.1's headers; Embree 3 keeps its ABI
//! within the major version, and the structs used here (`RTCRayHit`, `RTCIntersectContext`,
//! `RTCPointQuery` and its context, with one instance level) are laid out as in 3.13.5's.
//!
//! What a user gets by default: scene flags none, build quality medium (Embree's binned-SAH
//! builder; high would add spatial splits), one triangle mesh with an index buffer over
//! shared vertices (equal corners merged before timing, as parry3d's input is). The build time
//! is a user's whole path: new scene, new geometry, the copy of vertices and indices into
//! buffers Embree allocates (`rtcSetNewGeometryBuffer`), the commits. The device is made with
//! the input, outside the timing. `set_affinity` is not asked: Embree would pin the threads
//! entering its scheduler to cores of its choosing, while the run is pinned with `taskset`
//! (with one thread, Embree builds on the caller's, so its build runs on that core). Embree's
//! advice to set the flush-to-zero and denormals-are-zero modes is not followed either: they
//! would change the other libraries' arithmetic in the same process.
//!
//! Rays: `rtcIntersect1` with `tnear = 0`, `tfar = t_max`, all mask bits, the default
//! (incoherent) context; the hit's `t` is the ray's `tfar` afterwards. Shadow rays also go
//! through `rtcOccluded1`, which sets `tfar` to `-inf` when something blocks. Closest points:
//! `rtcPointQuery`, whose callback Embree calls for every triangle whose box reaches the
//! query sphere; the callback projects the point with bvhlab's `Triangle3::project_point`
//! (Embree leaves the primitive test to the user) and shrinks the sphere. Memory: the bytes
//! Embree reports to a device memory monitor while building the scene, less those it frees
//! (the builder's temporary memory), i.e. what the scene holds once committed. Embree does not
//! expose its nodes, so there is no node count or SAH cost.

use std::ffi::{CStr, c_void};
use std::ptr;
use std::sync::atomic::{AtomicIsize, Ordering};

use bvhlab::Triangle3;
use bvhlab::glam::Vec3;
use bvhlab_bench::workload::BenchRay;
use embree::sys;

use crate::library::{Library, TreeFacts, indexed_mesh};

/// Embree's triangle mesh.
pub struct Embree;

/// Embree's configuration string: its builder uses one thread (the comparison is
/// single-threaded and pinned to one core).
const CONFIG: &CStr = c"threads=1";

/// `RTC_INVALID_GEOMETRY_ID`: the hit's `geomID` when nothing was hit.
const INVALID_ID: u32 = u32::MAX;

/// One Embree device, with the running count of the bytes it holds (its memory monitor's).
struct Device {
    handle: sys::RTCDevice,
    /// Boxed so that its address, handed to Embree, stays put when the device moves. Dropped
    /// after `handle` is released (fields drop in order), since the release reports frees.
    allocated: Box<AtomicIsize>,
}

/// Embree's memory monitor: `bytes` is positive before an allocation, negative after a free.
#[allow(unsafe_code, reason = "an extern \"C\" callback that Embree calls")]
unsafe extern "C" fn count_bytes(user: *mut c_void, bytes: sys::ssize_t, _post: bool) -> bool {
    // SAFETY: `user` is the `AtomicIsize` boxed in the `Device` this monitor was set on, and
    // it outlives the device's handle (see `Device::allocated`).
    let counter = unsafe { &*user.cast::<AtomicIsize>() };
    counter.fetch_add(bytes, Ordering::Relaxed);
    true
}

impl Device {
    fn new() -> Self {
        let allocated = Box::new(AtomicIsize::new(0));
        #[allow(unsafe_code, reason = "Embree's C API")]
        // SAFETY: `CONFIG` is a NUL-terminated string; the device is checked for null before
        // use; the monitor's user pointer is `allocated`, which lives as long as the device.
        let handle = unsafe {
            let handle = sys::rtcNewDevice(CONFIG.as_ptr());
            assert!(!handle.is_null(), "Embree could not make a device");
            let user = ptr::from_ref::<AtomicIsize>(&allocated).cast_mut().cast();
            sys::rtcSetDeviceMemoryMonitorFunction(handle, Some(count_bytes), user);
            handle
        };
        Self { handle, allocated }
    }

    /// Panics with Embree's last error, if there was one.
    fn check(&self, what: &str) {
        #[allow(unsafe_code, reason = "Embree's C API")]
        // SAFETY: a live device handle.
        let error = unsafe { sys::rtcGetDeviceError(self.handle) };
        assert!(
            error == sys::RTCError::NONE,
            "Embree failed to {what}: {error:?}"
        );
    }
}

impl Drop for Device {
    fn drop(&mut self) {
        #[allow(unsafe_code, reason = "Embree's C API")]
        // SAFETY: the handle came from `rtcNewDevice`; every scene made on it borrows the
        // `EmbreeInput` that owns this device, so none outlives it.
        unsafe {
            sys::rtcReleaseDevice(self.handle);
        }
    }
}

/// The device and the mesh as Embree takes it (made before timing).
pub struct EmbreeInput {
    device: Device,
    vertices: Vec<[f32; 3]>,
    indices: Vec<[u32; 3]>,
    /// The triangles again, for the closest-point callback.
    tris: Vec<Triangle3>,
}

/// A committed Embree scene.
pub struct EmbreeScene<'a> {
    handle: sys::RTCScene,
    input: &'a EmbreeInput,
    /// Bytes Embree holds for the scene once committed.
    bytes: isize,
}

impl Drop for EmbreeScene<'_> {
    fn drop(&mut self) {
        #[allow(unsafe_code, reason = "Embree's C API")]
        // SAFETY: the handle came from `rtcNewScene` and is released once.
        unsafe {
            sys::rtcReleaseScene(self.handle);
        }
    }
}

/// Builds and commits a scene of one triangle mesh, copying the mesh into Embree's buffers.
fn build_scene(input: &EmbreeInput) -> EmbreeScene<'_> {
    let device = &input.device;
    let before = device.allocated.load(Ordering::Relaxed);
    #[allow(unsafe_code, reason = "Embree's C API")]
    // SAFETY: live device; the geometry gets its buffers (`new_buffer`) before it is
    // committed, and is released once attached (the scene keeps its own reference).
    let handle = unsafe {
        let scene = sys::rtcNewScene(device.handle);
        let geometry = sys::rtcNewGeometry(device.handle, sys::RTCGeometryType::TRIANGLE);
        new_buffer(
            device,
            geometry,
            sys::RTCBufferType::VERTEX,
            sys::RTCFormat::FLOAT3,
            &input.vertices,
            "allocate the vertex buffer",
        );
        new_buffer(
            device,
            geometry,
            sys::RTCBufferType::INDEX,
            sys::RTCFormat::UINT3,
            &input.indices,
            "allocate the index buffer",
        );
        sys::rtcCommitGeometry(geometry);
        sys::rtcAttachGeometry(scene, geometry);
        sys::rtcReleaseGeometry(geometry);
        sys::rtcCommitScene(scene);
        scene
    };
    device.check("build the scene");
    EmbreeScene {
        handle,
        input,
        bytes: device.allocated.load(Ordering::Relaxed) - before,
    }
}

/// Gives `geometry` (of `device`) a new buffer of `kind` holding a copy of `data`, one
/// element per vertex or triangle, laid out as `format` says (`f32` or `u32` triples here).
fn new_buffer<T: Copy>(
    device: &Device,
    geometry: sys::RTCGeometry,
    kind: sys::RTCBufferType,
    format: sys::RTCFormat,
    data: &[T],
    what: &str,
) {
    #[allow(unsafe_code, reason = "Embree's C API")]
    // SAFETY: a live geometry; `rtcSetNewGeometryBuffer` returns a buffer of
    // `data.len() * size_of::<T>()` bytes (padded by Embree for its 16-byte loads), checked
    // for an allocation error before exactly that many bytes of `data` are copied into it.
    unsafe {
        let buffer =
            sys::rtcSetNewGeometryBuffer(geometry, kind, 0, format, size_of::<T>(), data.len());
        device.check(what);
        ptr::copy_nonoverlapping(data.as_ptr(), buffer.cast::<T>(), data.len());
    }
}

/// `rtcInitIntersectContext` (an inline function of the header, so not in the bindings).
fn context() -> sys::RTCIntersectContext {
    sys::RTCIntersectContext {
        flags: sys::RTCIntersectContextFlags::INCOHERENT,
        filter: None,
        instID: [INVALID_ID],
    }
}

/// What the closest-point callback needs: the triangles, the point, the best distance so far.
struct NearestSearch<'a> {
    tris: &'a [Triangle3],
    point: Vec3,
    best: Option<f32>,
}

/// Embree's point-query callback: measures one triangle and shrinks the query's radius to its
/// distance when nearer (returning `true` tells Embree the radius changed).
#[allow(unsafe_code, reason = "an extern \"C\" callback that Embree calls")]
unsafe extern "C" fn nearest_triangle(args: *mut sys::RTCPointQueryFunctionArguments) -> bool {
    // SAFETY: Embree passes valid arguments whose `query` is the query handed to
    // `rtcPointQuery` and whose `userPtr` is the `NearestSearch` handed with it, alive and not
    // otherwise borrowed during the call.
    let (query, search, prim) = unsafe {
        let args = &*args;
        (
            &mut *args.query,
            &mut *args.userPtr.cast::<NearestSearch<'_>>(),
            args.primID as usize,
        )
    };
    // The mesh's triangles are in the input's order, so `primID` indexes them.
    let Some(tri) = search.tris.get(prim) else {
        return false;
    };
    let distance = (tri.project_point(search.point) - search.point).length();
    if distance < query.radius {
        query.radius = distance;
        search.best = Some(distance);
        true
    } else {
        false
    }
}

impl Library for Embree {
    const NAME: &'static str = "Embree 3 (default build: medium quality)";
    const HAS_CLOSEST: bool = true;
    const HAS_OCCLUSION: bool = true;
    type Input = EmbreeInput;
    type Tree<'a> = EmbreeScene<'a>;
    type Ray = sys::RTCRayHit;

    fn input(tris: &[Triangle3]) -> EmbreeInput {
        let (vertices, indices) = indexed_mesh(tris);
        EmbreeInput {
            device: Device::new(),
            vertices: vertices.iter().map(Vec3::to_array).collect(),
            indices,
            tris: tris.to_vec(),
        }
    }

    fn build(input: &EmbreeInput) -> EmbreeScene<'_> {
        build_scene(input)
    }

    fn ray(ray: &BenchRay) -> sys::RTCRayHit {
        let [org_x, org_y, org_z] = ray.origin.to_array();
        let [dir_x, dir_y, dir_z] = ray.dir.to_array();
        sys::RTCRayHit {
            ray: sys::RTCRay {
                org_x,
                org_y,
                org_z,
                tnear: 0.0,
                dir_x,
                dir_y,
                dir_z,
                time: 0.0,
                tfar: ray.t_max,
                mask: u32::MAX,
                id: 0,
                flags: 0,
            },
            hit: sys::RTCHit {
                Ng_x: 0.0,
                Ng_y: 0.0,
                Ng_z: 0.0,
                u: 0.0,
                v: 0.0,
                primID: INVALID_ID,
                geomID: INVALID_ID,
                instID: [INVALID_ID],
            },
        }
    }

    fn first_hit(tree: &EmbreeScene<'_>, ray: &sys::RTCRayHit) -> Option<f32> {
        let mut rayhit = *ray;
        let mut context = context();
        #[allow(unsafe_code, reason = "Embree's C API")]
        // SAFETY: a committed scene, a valid context, and a 16-byte aligned `RTCRayHit`
        // (the binding's type is `align(16)`) that Embree may write.
        unsafe {
            sys::rtcIntersect1(tree.handle, &raw mut context, &raw mut rayhit);
        }
        (rayhit.hit.geomID != INVALID_ID).then_some(rayhit.ray.tfar)
    }

    fn occluded(tree: &EmbreeScene<'_>, ray: &sys::RTCRayHit) -> bool {
        let mut shadow = ray.ray;
        let mut context = context();
        #[allow(unsafe_code, reason = "Embree's C API")]
        // SAFETY: a committed scene, a valid context, and a 16-byte aligned `RTCRay`.
        unsafe {
            sys::rtcOccluded1(tree.handle, &raw mut context, &raw mut shadow);
        }
        shadow.tfar == f32::NEG_INFINITY
    }

    fn closest_distance(tree: &EmbreeScene<'_>, point: Vec3) -> Option<f32> {
        let mut query = sys::RTCPointQuery {
            x: point.x,
            y: point.y,
            z: point.z,
            time: 0.0,
            radius: f32::INFINITY,
        };
        // `rtcInitPointQueryContext`, inline in the header.
        let mut context = sys::RTCPointQueryContext {
            world2inst: [[0.0; 16]],
            inst2world: [[0.0; 16]],
            instID: [INVALID_ID],
            instStackSize: 0,
        };
        let mut search = NearestSearch {
            tris: &tree.input.tris,
            point,
            best: None,
        };
        #[allow(unsafe_code, reason = "Embree's C API")]
        // SAFETY: a committed scene; the query, context and search live across the call,
        // which calls `nearest_triangle` with them on this thread only.
        unsafe {
            sys::rtcPointQuery(
                tree.handle,
                &raw mut query,
                &raw mut context,
                Some(nearest_triangle),
                (&raw mut search).cast(),
            );
        }
        search.best
    }

    fn facts(tree: &EmbreeScene<'_>) -> TreeFacts {
        TreeFacts {
            nodes: None,
            sah: None,
            bytes: usize::try_from(tree.bytes).ok(),
        }
    }
}
