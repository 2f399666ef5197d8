//! Mesa's llvmpipe, the software OpenGL rasterizer, driven off-screen
//! through EGL: no window, no GPU, no GL library at build time.
//!
//! `libEGL.so.1` is opened when [`Llvmpipe::new`] runs (`khronos-egl` with
//! dynamic loading), the GL functions are looked up through it (`glow`),
//! and the drawing goes into a framebuffer object of colour (RGBA8) and
//! depth (32-bit float), so the same work as rasterlab's target. On Debian
//! the run-time packages are `libegl1 libegl-mesa0 libgl1-mesa-dri`; when
//! they are missing, [`Llvmpipe::new`] says so in its error and the callers
//! print the rows they could not measure as skipped.
//!
//! The display is EGL's surfaceless platform (`EGL_MESA_platform_surfaceless`).
//! llvmpipe reads its rasterizer thread count (`LP_NUM_THREADS`) once per
//! display, when the display is initialised, and a process has one
//! surfaceless display: a second thread count alive at the same time is
//! given the display of Mesa's software device (`EGL_EXT_platform_device`
//! with `EGL_MESA_device_software`), also llvmpipe, also without window or
//! GPU. So at most two thread counts can be alive at once.
//!
//! Coordinates: rasterlab's screen has y growing down, GL's window y grows
//! up. Every transform here negates clip-space y ([`Llvmpipe::mesh_transform`])
//! or maps pixels straight to window coordinates
//! ([`Llvmpipe::window_transform`]), so a point at rasterlab's `(x, y)`
//! lands at GL's window `(x, y)`, and row `r` of [`Llvmpipe::coverage`] is
//! rasterlab's row `r`. The negation mirrors the winding, so a mesh's front
//! faces (counter-clockwise in rasterlab) are clockwise for GL
//! (`glFrontFace(GL_CW)`).
//!
//! Included by `benches/side_by_side.rs`, `tests/llvmpipe.rs` and
//! `tests/llvmpipe_textures.rs` with
//! `#[path]`; it depends on `khronos-egl` and `glow` only.

use glow::HasContext;
use khronos_egl as egl;
use std::sync::Mutex;

/// `EGL_PLATFORM_SURFACELESS_MESA`.
const PLATFORM_SURFACELESS: egl::Enum = 0x31DD;
/// `EGL_PLATFORM_DEVICE_EXT`.
const PLATFORM_DEVICE: egl::Enum = 0x313F;
/// `GL_TEXTURE_MAX_ANISOTROPY_EXT` (EXT_texture_filter_anisotropic).
#[allow(dead_code)] // drawn by the texture tests and the bench only
const TEXTURE_MAX_ANISOTROPY: u32 = 0x84FE;
/// `GL_MAX_TEXTURE_MAX_ANISOTROPY_EXT`.
#[allow(dead_code)] // drawn by the texture tests and the bench only
const MAX_TEXTURE_MAX_ANISOTROPY: u32 = 0x84FF;

/// The two displays and the thread count each was initialised with.
static DISPLAYS: Mutex<[Option<usize>; 2]> = Mutex::new([None, None]);

/// One vertex: a position (model space for a mesh, pixels and depth for
/// window triangles) and a light intensity (the grey it is drawn in).
#[derive(Copy, Clone, Debug, PartialEq)]
#[repr(C)]
pub struct Vertex {
    /// Position.
    pub position: [f32; 3],
    /// Light intensity in `[0, 1]`.
    pub light: f32,
}

/// One vertex of a textured shape: a position (model space) and a
/// texture coordinate, `(0, 0)` at the top-left corner of texel `(0, 0)`
/// of the first row uploaded, as rasterlab's.
#[allow(dead_code)] // drawn by the texture tests and the bench only
#[derive(Copy, Clone, Debug, PartialEq)]
#[repr(C)]
pub struct TexturedVertex {
    /// Position.
    pub position: [f32; 3],
    /// Texture coordinate.
    pub uv: [f32; 2],
}

/// One level of a mip pyramid to upload: RGBA8 texels, row by row, row 0
/// first (texture coordinate t = 0).
#[allow(dead_code)] // drawn by the texture tests and the bench only
#[derive(Clone, Debug, PartialEq)]
pub struct Level {
    /// Width in texels.
    pub width: u32,
    /// Height in texels.
    pub height: u32,
    /// `width * height * 4` bytes.
    pub rgba: Vec<u8>,
}

/// Indexed triangles uploaded to the GL.
pub struct Shape {
    vertex_array: glow::VertexArray,
    buffers: [glow::Buffer; 2],
    indices: i32,
}

/// How a shape is drawn.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct DrawState {
    /// Depth test `less` with depth writes (the depth is cleared to 1.0
    /// first); without it, no depth buffer is touched.
    pub depth: bool,
    /// Back faces culled (front faces clockwise in GL's window, see the
    /// module docs).
    pub cull_back: bool,
}

impl DrawState {
    /// No depth test, no culling: a plane drawn alone.
    pub const NONE: DrawState = DrawState {
        depth: false,
        cull_back: false,
    };
}

/// An llvmpipe context with an off-screen colour and depth target.
pub struct Llvmpipe {
    egl: egl::DynamicInstance<egl::EGL1_5>,
    display: egl::Display,
    context: egl::Context,
    gl: glow::Context,
    program: glow::Program,
    transform: glow::UniformLocation,
    textured: glow::Program,
    textured_transform: glow::UniformLocation,
    query: glow::Query,
    width: u32,
    height: u32,
    threads: usize,
}

impl Llvmpipe {
    /// llvmpipe with `threads` rasterizer threads (`LP_NUM_THREADS`; 0
    /// rasterizes on the calling thread) and a `width` x `height` target,
    /// current on this thread. The error says what is missing.
    pub fn new(width: u32, height: u32, threads: usize) -> Result<Llvmpipe, String> {
        // SAFETY: libEGL is the system's EGL loader; khronos-egl checks
        // that it exports the EGL 1.5 entry points it binds.
        let egl = unsafe { egl::DynamicInstance::<egl::EGL1_5>::load_required() }.map_err(|e| {
            format!(
                "no libEGL.so.1 ({e}): install Mesa (Debian: libegl1 libegl-mesa0 libgl1-mesa-dri)"
            )
        })?;
        let display = open_display(&egl, threads)?;
        let (context, gl) = open_context(&egl, display, (3, 3))?;
        // SAFETY: plain GL calls on the current context.
        let renderer = unsafe { gl.get_parameter_string(glow::RENDERER) };
        if !renderer.contains("llvmpipe") {
            return Err(format!("EGL gave the renderer {renderer:?}, not llvmpipe"));
        }
        // SAFETY: as above.
        let (program, transform, query) = unsafe { set_up(&gl, width, height)? };
        // SAFETY: as above.
        let textured = unsafe { textured_program(&gl)? };
        // SAFETY: as above.
        let textured_transform = unsafe { gl.get_uniform_location(textured, "transform") }
            .ok_or("no uniform `transform` in the textured program")?;
        Ok(Llvmpipe {
            egl,
            display,
            context,
            gl,
            program,
            transform,
            textured,
            textured_transform,
            query,
            width,
            height,
            threads,
        })
    }

    /// The GL renderer string, e.g. `llvmpipe (LLVM 15.0.6, 256 bits)`.
    pub fn renderer(&self) -> String {
        self.make_current();
        // SAFETY: a GL call on the current context.
        unsafe { self.gl.get_parameter_string(glow::RENDERER) }
    }

    /// The rasterizer threads asked for.
    pub fn threads(&self) -> usize {
        self.threads
    }

    /// Makes this context current on the calling thread (needed when two
    /// llvmpipe contexts are used in turn).
    pub fn make_current(&self) {
        self.egl
            .make_current(self.display, None, None, Some(self.context))
            .expect("an llvmpipe context made current again");
    }

    /// Uploads indexed triangles.
    pub fn shape(&self, vertices: &[Vertex], indices: &[u32]) -> Shape {
        self.make_current();
        let gl = &self.gl;
        // SAFETY: GL calls on the current context; the slices outlive the
        // calls, and the attribute layout is `Vertex`'s (repr(C), 16 bytes).
        unsafe {
            let vertex_array = gl.create_vertex_array().expect("a vertex array");
            gl.bind_vertex_array(Some(vertex_array));
            let vbo = gl.create_buffer().expect("a vertex buffer");
            gl.bind_buffer(glow::ARRAY_BUFFER, Some(vbo));
            gl.buffer_data_u8_slice(glow::ARRAY_BUFFER, as_bytes(vertices), glow::STATIC_DRAW);
            gl.enable_vertex_attrib_array(0);
            gl.vertex_attrib_pointer_f32(0, 3, glow::FLOAT, false, 16, 0);
            gl.enable_vertex_attrib_array(1);
            gl.vertex_attrib_pointer_f32(1, 1, glow::FLOAT, false, 16, 12);
            let ebo = gl.create_buffer().expect("an index buffer");
            gl.bind_buffer(glow::ELEMENT_ARRAY_BUFFER, Some(ebo));
            gl.buffer_data_u8_slice(
                glow::ELEMENT_ARRAY_BUFFER,
                as_bytes(indices),
                glow::STATIC_DRAW,
            );
            gl.bind_vertex_array(None);
            Shape {
                vertex_array,
                buffers: [vbo, ebo],
                indices: indices.len() as i32,
            }
        }
    }

    /// Frees a shape's buffers.
    pub fn delete(&self, shape: Shape) {
        self.make_current();
        // SAFETY: GL calls on the current context, on objects it made.
        unsafe {
            self.gl.delete_vertex_array(shape.vertex_array);
            for buffer in shape.buffers {
                self.gl.delete_buffer(buffer);
            }
        }
    }

    /// A mesh transform for GL: rasterlab's model-view-projection matrix
    /// (column-major) with clip-space y negated, so GL's window
    /// coordinates are rasterlab's screen coordinates.
    pub fn mesh_transform(mvp: [f32; 16]) -> [f32; 16] {
        let mut m = mvp;
        for column in 0..4 {
            m[column * 4 + 1] = -m[column * 4 + 1];
        }
        m
    }

    /// The transform for window triangles: a vertex's position is
    /// `(x, y, depth)` in pixels (rasterlab's screen) and `[0, 1]`.
    pub fn window_transform(&self) -> [f32; 16] {
        let (sx, sy) = (2.0 / self.width as f32, 2.0 / self.height as f32);
        [
            sx, 0.0, 0.0, 0.0, //
            0.0, sy, 0.0, 0.0, //
            0.0, 0.0, 2.0, 0.0, //
            -1.0, -1.0, -1.0, 1.0,
        ]
    }

    /// Clears the depth (when drawing with depth) or the colour (when
    /// not), draws `shape` and waits until llvmpipe has finished.
    pub fn draw(&self, shape: &Shape, transform: &[f32; 16], state: DrawState) {
        self.submit(shape, transform, state);
        // SAFETY: a GL call on the current context.
        unsafe { self.gl.finish() };
    }

    /// The fragments `shape` produces under `state`, but with every one
    /// passing the depth test (the depth test set to `always`): the count
    /// rasterlab's back-ends call "fragments emitted".
    pub fn fragments(&self, shape: &Shape, transform: &[f32; 16], cull_back: bool) -> u64 {
        let gl = &self.gl;
        self.make_current();
        // SAFETY: GL calls on the current context.
        unsafe {
            gl.begin_query(glow::SAMPLES_PASSED, self.query);
            self.submit(
                shape,
                transform,
                DrawState {
                    depth: false,
                    cull_back,
                },
            );
            gl.end_query(glow::SAMPLES_PASSED);
            u64::from(gl.get_query_parameter_u32(self.query, glow::QUERY_RESULT))
        }
    }

    /// The pixels the last draw covered (alpha not zero), row by row, row
    /// 0 first (rasterlab's top row, see the module docs).
    #[allow(dead_code)] // the tests read pixels back; the bench only times
    pub fn coverage(&self) -> Vec<bool> {
        self.rgba().chunks_exact(4).map(|p| p[3] != 0).collect()
    }

    /// The target's RGBA8 colour, row by row, row 0 first (rasterlab's
    /// top row, see the module docs), as rasterlab's target holds it.
    #[allow(dead_code)] // the tests read pixels back; the bench only times
    pub fn rgba(&self) -> Vec<u8> {
        self.make_current();
        let mut rgba = vec![0u8; self.width as usize * self.height as usize * 4];
        // SAFETY: a GL call on the current context; the buffer holds the
        // whole target in RGBA8.
        unsafe {
            self.gl.read_pixels(
                0,
                0,
                self.width as i32,
                self.height as i32,
                glow::RGBA,
                glow::UNSIGNED_BYTE,
                glow::PixelPackData::Slice(Some(&mut rgba)),
            );
        }
        rgba
    }

    /// Uploads textured triangles (the position and the texture
    /// coordinate of each vertex).
    #[allow(dead_code)] // drawn by the texture tests and the bench only
    pub fn textured_shape(&self, vertices: &[TexturedVertex], indices: &[u32]) -> Shape {
        self.make_current();
        let gl = &self.gl;
        // SAFETY: GL calls on the current context; the slices outlive the
        // calls, and the attribute layout is `TexturedVertex`'s (repr(C),
        // 20 bytes).
        unsafe {
            let vertex_array = gl.create_vertex_array().expect("a vertex array");
            gl.bind_vertex_array(Some(vertex_array));
            let vbo = gl.create_buffer().expect("a vertex buffer");
            gl.bind_buffer(glow::ARRAY_BUFFER, Some(vbo));
            gl.buffer_data_u8_slice(glow::ARRAY_BUFFER, as_bytes(vertices), glow::STATIC_DRAW);
            gl.enable_vertex_attrib_array(0);
            gl.vertex_attrib_pointer_f32(0, 3, glow::FLOAT, false, 20, 0);
            gl.enable_vertex_attrib_array(1);
            gl.vertex_attrib_pointer_f32(1, 2, glow::FLOAT, false, 20, 12);
            let ebo = gl.create_buffer().expect("an index buffer");
            gl.bind_buffer(glow::ELEMENT_ARRAY_BUFFER, Some(ebo));
            gl.buffer_data_u8_slice(
                glow::ELEMENT_ARRAY_BUFFER,
                as_bytes(indices),
                glow::STATIC_DRAW,
            );
            gl.bind_vertex_array(None);
            Shape {
                vertex_array,
                buffers: [vbo, ebo],
                indices: indices.len() as i32,
            }
        }
    }

    /// The most anisotropy the context offers
    /// (`GL_MAX_TEXTURE_MAX_ANISOTROPY`), or `None` without
    /// `GL_EXT_texture_filter_anisotropic` (or its ARB twin).
    #[allow(dead_code)] // drawn by the texture tests and the bench only
    pub fn max_anisotropy(&self) -> Option<f32> {
        self.make_current();
        let extensions = self.gl.supported_extensions();
        let offered = [
            "GL_EXT_texture_filter_anisotropic",
            "GL_ARB_texture_filter_anisotropic",
        ]
        .iter()
        .any(|e| extensions.contains(*e));
        // SAFETY: a GL call on the current context, of a parameter the
        // extension defines.
        offered.then(|| unsafe { self.gl.get_parameter_f32(MAX_TEXTURE_MAX_ANISOTROPY) })
    }

    /// A mipmapped texture whose levels are `levels`, uploaded one by one
    /// (`glTexImage2D` for each, no `glGenerateMipmap`), so that the GL
    /// filters the very pyramid given. Sampled with `GL_LINEAR_MIPMAP_LINEAR`
    /// (trilinear), `GL_LINEAR` when magnified, repeating both ways; with
    /// `anisotropy` above 1, `GL_TEXTURE_MAX_ANISOTROPY` set to it. The
    /// texels are plain RGBA8 (`GL_RGBA8`, not sRGB): the GL filters the
    /// stored values, as rasterlab does. An error when the levels do not
    /// form a pyramid from the first down to 1x1, or the anisotropy is not
    /// offered.
    #[allow(dead_code)] // drawn by the texture tests and the bench only
    pub fn mipmapped(&self, levels: &[Level], anisotropy: f32) -> Result<glow::Texture, String> {
        let Some(first) = levels.first() else {
            return Err("a texture needs at least one level".into());
        };
        let (mut w, mut h) = (first.width, first.height);
        for (i, level) in levels.iter().enumerate() {
            if (level.width, level.height) != (w, h) || level.rgba.len() != (w * h * 4) as usize {
                return Err(format!(
                    "level {i} is {}x{} with {} bytes, not {w}x{h}",
                    level.width,
                    level.height,
                    level.rgba.len()
                ));
            }
            (w, h) = ((w / 2).max(1), (h / 2).max(1));
        }
        if levels.last().map(|l| (l.width, l.height)) != Some((1, 1)) {
            return Err("the levels stop before 1x1".into());
        }
        if anisotropy > 1.0 {
            match self.max_anisotropy() {
                Some(max) if anisotropy <= max => {}
                Some(max) => {
                    return Err(format!(
                        "llvmpipe offers {max}x anisotropy, not {anisotropy}x"
                    ))
                }
                None => return Err("no GL_EXT_texture_filter_anisotropic".into()),
            }
        }
        self.make_current();
        let gl = &self.gl;
        // SAFETY: GL calls on the current context; each level's bytes hold
        // its width x height RGBA8 texels (checked above).
        unsafe {
            let texture = gl.create_texture()?;
            gl.bind_texture(glow::TEXTURE_2D, Some(texture));
            gl.pixel_store_i32(glow::UNPACK_ALIGNMENT, 1);
            for (i, level) in levels.iter().enumerate() {
                gl.tex_image_2d(
                    glow::TEXTURE_2D,
                    i as i32,
                    glow::RGBA8 as i32,
                    level.width as i32,
                    level.height as i32,
                    0,
                    glow::RGBA,
                    glow::UNSIGNED_BYTE,
                    glow::PixelUnpackData::Slice(Some(&level.rgba)),
                );
            }
            let parameters = [
                (glow::TEXTURE_BASE_LEVEL, 0),
                (glow::TEXTURE_MAX_LEVEL, levels.len() as i32 - 1),
                (glow::TEXTURE_MIN_FILTER, glow::LINEAR_MIPMAP_LINEAR as i32),
                (glow::TEXTURE_MAG_FILTER, glow::LINEAR as i32),
                (glow::TEXTURE_WRAP_S, glow::REPEAT as i32),
                (glow::TEXTURE_WRAP_T, glow::REPEAT as i32),
            ];
            for (name, value) in parameters {
                gl.tex_parameter_i32(glow::TEXTURE_2D, name, value);
            }
            if anisotropy > 1.0 {
                gl.tex_parameter_f32(glow::TEXTURE_2D, TEXTURE_MAX_ANISOTROPY, anisotropy);
            }
            gl.bind_texture(glow::TEXTURE_2D, None);
            Ok(texture)
        }
    }

    /// Frees a texture.
    #[allow(dead_code)] // drawn by the texture tests and the bench only
    pub fn delete_texture(&self, texture: glow::Texture) {
        self.make_current();
        // SAFETY: a GL call on the current context, on a texture it made.
        unsafe { self.gl.delete_texture(texture) };
    }

    /// Clears the colour to `clear` (RGBA8), draws `shape` sampling
    /// `texture` in its fragment shader (`texture(sampler2D, uv)`, the
    /// derivatives and level of detail llvmpipe's own) without depth
    /// test or culling, and waits until llvmpipe has finished.
    #[allow(dead_code)] // drawn by the texture tests and the bench only
    pub fn draw_textured(
        &self,
        shape: &Shape,
        transform: &[f32; 16],
        texture: glow::Texture,
        clear: [u8; 4],
        state: DrawState,
    ) {
        self.make_current();
        let gl = &self.gl;
        let [r, g, b, a] = clear.map(|c| f32::from(c) / 255.0);
        // SAFETY: GL calls on the current context, with objects it made.
        unsafe {
            self.apply(state);
            gl.clear_color(r, g, b, a);
            gl.clear(glow::COLOR_BUFFER_BIT);
            gl.clear_color(0.0, 0.0, 0.0, 0.0);
            gl.use_program(Some(self.textured));
            gl.uniform_matrix_4_f32_slice(Some(&self.textured_transform), false, transform);
            gl.active_texture(glow::TEXTURE0);
            gl.bind_texture(glow::TEXTURE_2D, Some(texture));
            gl.bind_vertex_array(Some(shape.vertex_array));
            gl.draw_elements(glow::TRIANGLES, shape.indices, glow::UNSIGNED_INT, 0);
            gl.bind_vertex_array(None);
            gl.bind_texture(glow::TEXTURE_2D, None);
            gl.finish();
        }
    }

    fn submit(&self, shape: &Shape, transform: &[f32; 16], state: DrawState) {
        self.make_current();
        let gl = &self.gl;
        // SAFETY: GL calls on the current context, with objects it made.
        unsafe {
            self.apply(state);
            if !state.depth {
                gl.clear(glow::COLOR_BUFFER_BIT);
            }
            gl.use_program(Some(self.program));
            gl.uniform_matrix_4_f32_slice(Some(&self.transform), false, transform);
            gl.bind_vertex_array(Some(shape.vertex_array));
            gl.draw_elements(glow::TRIANGLES, shape.indices, glow::UNSIGNED_INT, 0);
            gl.bind_vertex_array(None);
        }
    }
}

impl Llvmpipe {
    /// Sets `state`'s depth test (clearing the depth buffer when there is
    /// one) and culling.
    ///
    /// # Safety
    /// The context must be current.
    unsafe fn apply(&self, state: DrawState) {
        let gl = &self.gl;
        // SAFETY: the caller made the context current.
        unsafe {
            if state.depth {
                gl.enable(glow::DEPTH_TEST);
                gl.depth_func(glow::LESS);
                gl.depth_mask(true);
                gl.clear(glow::DEPTH_BUFFER_BIT);
            } else {
                gl.disable(glow::DEPTH_TEST);
                gl.depth_mask(false);
            }
            if state.cull_back {
                gl.enable(glow::CULL_FACE);
                gl.cull_face(glow::BACK);
                gl.front_face(glow::CW);
            } else {
                gl.disable(glow::CULL_FACE);
            }
        }
    }
}

impl Drop for Llvmpipe {
    fn drop(&mut self) {
        let _ = self.egl.make_current(self.display, None, None, None);
        let _ = self.egl.destroy_context(self.display, self.context);
    }
}

/// The display for `threads` rasterizer threads: the surfaceless one,
/// or, when that one already runs another thread count, the software
/// device's (see the module docs).
fn open_display(
    egl: &egl::DynamicInstance<egl::EGL1_5>,
    threads: usize,
) -> Result<egl::Display, String> {
    let mut displays = DISPLAYS.lock().unwrap_or_else(|e| e.into_inner());
    let slot = match *displays {
        [None, _] => 0,
        [Some(t), _] if t == threads => 0,
        [_, None] => 1,
        [_, Some(t)] if t == threads => 1,
        [Some(a), Some(b)] => {
            return Err(format!(
                "llvmpipe already runs with {a} and {b} threads in this process (at most two thread counts at once)"
            ))
        }
    };
    // SAFETY: the native display of the surfaceless platform is
    // EGL_DEFAULT_DISPLAY; the device's is the EGLDeviceEXT found below.
    let display = unsafe {
        if slot == 0 {
            egl.get_platform_display(
                PLATFORM_SURFACELESS,
                egl::DEFAULT_DISPLAY,
                &[egl::ATTRIB_NONE],
            )
        } else {
            let device = software_device(egl)?;
            egl.get_platform_display(PLATFORM_DEVICE, device, &[egl::ATTRIB_NONE])
        }
    }
    .map_err(|e| {
        format!("no EGL surfaceless display ({e}): install Mesa's EGL (Debian: libegl-mesa0)")
    })?;
    if displays[slot].is_none() {
        let before = std::env::var_os("LP_NUM_THREADS");
        std::env::set_var("LP_NUM_THREADS", threads.to_string());
        let initialised = egl.initialize(display);
        match before {
            Some(value) => std::env::set_var("LP_NUM_THREADS", value),
            None => std::env::remove_var("LP_NUM_THREADS"),
        }
        initialised.map_err(|e| {
            format!("eglInitialize: {e} (Mesa's DRI drivers missing? Debian: libgl1-mesa-dri)")
        })?;
        displays[slot] = Some(threads);
    }
    Ok(display)
}

/// Mesa's software EGL device (`EGL_MESA_device_software`).
fn software_device(
    egl: &egl::DynamicInstance<egl::EGL1_5>,
) -> Result<egl::NativeDisplayType, String> {
    type QueryDevices = unsafe extern "system" fn(i32, *mut *mut std::ffi::c_void, *mut i32) -> u32;
    type QueryDeviceString =
        unsafe extern "system" fn(*mut std::ffi::c_void, i32) -> *const std::ffi::c_char;
    let (Some(devices_fn), Some(string_fn)) = (
        egl.get_proc_address("eglQueryDevicesEXT"),
        egl.get_proc_address("eglQueryDeviceStringEXT"),
    ) else {
        return Err("EGL has no EGL_EXT_device_enumeration for a second llvmpipe display".into());
    };
    // SAFETY: the two entry points have the signatures of
    // EGL_EXT_device_enumeration and EGL_EXT_device_query; the array holds
    // the 16 devices asked for at most, and a device string is a C string
    // owned by EGL.
    unsafe {
        let query_devices: QueryDevices = std::mem::transmute(devices_fn);
        let query_string: QueryDeviceString = std::mem::transmute(string_fn);
        let mut devices = [std::ptr::null_mut(); 16];
        let mut count = 0;
        if query_devices(16, devices.as_mut_ptr(), &mut count) == 0 {
            return Err("eglQueryDevicesEXT failed".into());
        }
        for &device in &devices[..count.clamp(0, 16) as usize] {
            let extensions = query_string(device, egl::EXTENSIONS);
            if !extensions.is_null()
                && std::ffi::CStr::from_ptr(extensions)
                    .to_string_lossy()
                    .contains("EGL_MESA_device_software")
            {
                return Ok(device);
            }
        }
    }
    Err("no Mesa software EGL device for a second llvmpipe display".into())
}

/// A core-profile OpenGL context of `version` on `display`, current on
/// this thread, with its GL functions.
fn open_context(
    egl: &egl::DynamicInstance<egl::EGL1_5>,
    display: egl::Display,
    version: (i32, i32),
) -> Result<(egl::Context, glow::Context), String> {
    egl.bind_api(egl::OPENGL_API)
        .map_err(|e| format!("eglBindAPI(OpenGL): {e}"))?;
    let attributes = [
        egl::CONTEXT_MAJOR_VERSION,
        version.0,
        egl::CONTEXT_MINOR_VERSION,
        version.1,
        egl::CONTEXT_OPENGL_PROFILE_MASK,
        egl::CONTEXT_OPENGL_CORE_PROFILE_BIT,
        egl::NONE,
    ];
    // SAFETY: a null config is EGL_NO_CONFIG_KHR (EGL_KHR_no_config_context,
    // which Mesa offers): the context draws only into framebuffer objects.
    let no_config = unsafe { egl::Config::from_ptr(std::ptr::null_mut()) };
    let context = egl
        .create_context(display, no_config, None, &attributes)
        .map_err(|e| {
            format!(
                "eglCreateContext(OpenGL {}.{} core): {e}",
                version.0, version.1
            )
        })?;
    egl.make_current(display, None, None, Some(context))
        .map_err(|e| format!("eglMakeCurrent: {e}"))?;
    // SAFETY: the context is current; eglGetProcAddress returns GL
    // entry points of that context's vendor (or null, which glow
    // turns into a panic only when the function is called).
    let gl = unsafe {
        glow::Context::from_loader_function(|name| {
            egl.get_proc_address(name)
                .map_or(std::ptr::null(), |f| f as *const std::ffi::c_void)
        })
    };
    Ok((context, gl))
}

/// llvmpipe multisampling: the coverage mask of each pixel a triangle
/// touches, as its fragment shader sees it (`gl_SampleMaskIn`, GLSL 4.00,
/// so an OpenGL 4.0 core context), and the samples it really wrote.
#[allow(dead_code)] // the tests read masks; the bench does not
pub struct MaskReader {
    egl: egl::DynamicInstance<egl::EGL1_5>,
    display: egl::Display,
    context: egl::Context,
    gl: glow::Context,
    draw: glow::Program,
    transform: glow::UniformLocation,
    resolve: glow::Program,
    multisampled: glow::Framebuffer,
    texture: glow::Texture,
    resolved: glow::Framebuffer,
    samples: i32,
    width: u32,
    height: u32,
}

#[allow(dead_code)] // the tests read masks; the bench does not
impl MaskReader {
    /// llvmpipe drawing into a `width` x `height` target of `samples`
    /// samples per pixel (at most `GL_MAX_SAMPLES`); the error says what
    /// is missing.
    pub fn new(width: u32, height: u32, samples: i32) -> Result<MaskReader, String> {
        // SAFETY: as in `Llvmpipe::new`.
        let egl = unsafe { egl::DynamicInstance::<egl::EGL1_5>::load_required() }.map_err(|e| {
            format!(
                "no libEGL.so.1 ({e}): install Mesa (Debian: libegl1 libegl-mesa0 libgl1-mesa-dri)"
            )
        })?;
        let display = open_display(&egl, 1)?;
        let (context, gl) = open_context(&egl, display, (4, 0))?;
        // SAFETY: GL calls on the current context.
        unsafe {
            let renderer = gl.get_parameter_string(glow::RENDERER);
            if !renderer.contains("llvmpipe") {
                return Err(format!("EGL gave the renderer {renderer:?}, not llvmpipe"));
            }
            let max = gl.get_parameter_i32(glow::MAX_SAMPLES);
            if samples > max {
                return Err(format!(
                    "llvmpipe offers at most {max} samples, not {samples}"
                ));
            }
            let target =
                |ms: bool, format: u32| -> Result<(glow::Framebuffer, glow::Texture), String> {
                    let texture = gl.create_texture()?;
                    let framebuffer = gl.create_framebuffer()?;
                    gl.bind_framebuffer(glow::FRAMEBUFFER, Some(framebuffer));
                    if ms {
                        gl.bind_texture(glow::TEXTURE_2D_MULTISAMPLE, Some(texture));
                        gl.tex_image_2d_multisample(
                            glow::TEXTURE_2D_MULTISAMPLE,
                            samples,
                            format as i32,
                            width as i32,
                            height as i32,
                            true,
                        );
                        gl.framebuffer_texture_2d(
                            glow::FRAMEBUFFER,
                            glow::COLOR_ATTACHMENT0,
                            glow::TEXTURE_2D_MULTISAMPLE,
                            Some(texture),
                            0,
                        );
                    } else {
                        gl.bind_texture(glow::TEXTURE_2D, Some(texture));
                        gl.tex_storage_2d(glow::TEXTURE_2D, 1, format, width as i32, height as i32);
                        gl.framebuffer_texture_2d(
                            glow::FRAMEBUFFER,
                            glow::COLOR_ATTACHMENT0,
                            glow::TEXTURE_2D,
                            Some(texture),
                            0,
                        );
                    }
                    let status = gl.check_framebuffer_status(glow::FRAMEBUFFER);
                    if status != glow::FRAMEBUFFER_COMPLETE {
                        return Err(format!("framebuffer incomplete: 0x{status:x}"));
                    }
                    Ok((framebuffer, texture))
                };
            let (multisampled, texture) = target(true, glow::R32UI)?;
            let (resolved, _) = target(false, glow::RG32UI)?;
            let draw = program(
                &gl,
                "#version 400 core\n\
                 layout(location = 0) in vec3 position;\n\
                 uniform mat4 transform;\n\
                 void main() { gl_Position = transform * vec4(position, 1.0); }\n",
                "#version 400 core\n\
                 out uint mask;\n\
                 void main() { mask = uint(gl_SampleMaskIn[0]); }\n",
            )?;
            // A triangle over the whole target; each pixel gathers its
            // samples: which were written (bit i for sample i) and the
            // mask the fragment shader saw.
            let resolve = program(
                &gl,
                "#version 400 core\n\
                 void main() {\n\
                   vec2 p = vec2(float((gl_VertexID & 1) * 4 - 1), float((gl_VertexID & 2) * 2 - 1));\n\
                   gl_Position = vec4(p, 0.0, 1.0);\n\
                 }\n",
                &format!(
                    "#version 400 core\n\
                     uniform usampler2DMS samples;\n\
                     out uvec2 masks;\n\
                     void main() {{\n\
                       uint written = 0u, seen = 0u;\n\
                       for (int i = 0; i < {samples}; i++) {{\n\
                         uint m = texelFetch(samples, ivec2(gl_FragCoord.xy), i).r;\n\
                         if (m != 0u) {{ written |= 1u << i; seen |= m; }}\n\
                       }}\n\
                       masks = uvec2(written, seen);\n\
                     }}\n"
                ),
            )?;
            let transform = gl
                .get_uniform_location(draw, "transform")
                .ok_or("no uniform `transform`")?;
            gl.viewport(0, 0, width as i32, height as i32);
            Ok(MaskReader {
                egl,
                display,
                context,
                gl,
                draw,
                transform,
                resolve,
                multisampled,
                texture,
                resolved,
                samples,
                width,
                height,
            })
        }
    }

    /// The GL renderer string.
    pub fn renderer(&self) -> String {
        self.make_current();
        // SAFETY: a GL call on the current context.
        unsafe { self.gl.get_parameter_string(glow::RENDERER) }
    }

    /// Sample `i`'s position in its pixel, in GL's window coordinates
    /// (`glGetMultisamplefv(GL_SAMPLE_POSITION)`: x right, y up, in [0, 1]).
    pub fn sample_position(&self, i: u32) -> (f32, f32) {
        type GetMultisample = unsafe extern "system" fn(u32, u32, *mut f32);
        self.make_current();
        let f = self
            .egl
            .get_proc_address("glGetMultisamplefv")
            .expect("glGetMultisamplefv (OpenGL 3.2)");
        let mut xy = [0.0f32; 2];
        // SAFETY: the entry point has glGetMultisamplefv's signature and
        // writes two floats; the multisampled framebuffer is bound.
        unsafe {
            self.gl
                .bind_framebuffer(glow::FRAMEBUFFER, Some(self.multisampled));
            let get: GetMultisample = std::mem::transmute(f);
            get(glow::SAMPLE_POSITION, i, xy.as_mut_ptr());
        }
        (xy[0], xy[1])
    }

    /// The triangle `corners` (window coordinates, pixels) drawn alone:
    /// per pixel, row 0 first (window y = 0), the samples written (bit i
    /// for sample i) and the `gl_SampleMaskIn` its fragment shader saw.
    pub fn masks(&self, corners: [(f32, f32); 3]) -> Vec<(u32, u32)> {
        self.make_current();
        let gl = &self.gl;
        let (w, h) = (self.width as f32, self.height as f32);
        let transform = [
            2.0 / w,
            0.0,
            0.0,
            0.0, //
            0.0,
            2.0 / h,
            0.0,
            0.0, //
            0.0,
            0.0,
            1.0,
            0.0, //
            -1.0,
            -1.0,
            0.0,
            1.0,
        ];
        let vertices: Vec<f32> = corners.iter().flat_map(|&(x, y)| [x, y, 0.0]).collect();
        let mut out = vec![0u32; self.width as usize * self.height as usize * 2];
        // SAFETY: GL calls on the current context, with objects it made;
        // the read-back buffer holds the whole target in RG32UI.
        unsafe {
            gl.bind_framebuffer(glow::FRAMEBUFFER, Some(self.multisampled));
            gl.clear_buffer_u32_slice(glow::COLOR, 0, &[0, 0, 0, 0]);
            let vertex_array = gl.create_vertex_array().expect("a vertex array");
            gl.bind_vertex_array(Some(vertex_array));
            let vbo = gl.create_buffer().expect("a vertex buffer");
            gl.bind_buffer(glow::ARRAY_BUFFER, Some(vbo));
            gl.buffer_data_u8_slice(glow::ARRAY_BUFFER, as_bytes(&vertices), glow::STATIC_DRAW);
            gl.enable_vertex_attrib_array(0);
            gl.vertex_attrib_pointer_f32(0, 3, glow::FLOAT, false, 12, 0);
            gl.use_program(Some(self.draw));
            gl.uniform_matrix_4_f32_slice(Some(&self.transform), false, &transform);
            gl.draw_arrays(glow::TRIANGLES, 0, 3);
            gl.bind_framebuffer(glow::FRAMEBUFFER, Some(self.resolved));
            gl.use_program(Some(self.resolve));
            gl.active_texture(glow::TEXTURE0);
            gl.bind_texture(glow::TEXTURE_2D_MULTISAMPLE, Some(self.texture));
            gl.draw_arrays(glow::TRIANGLES, 0, 3);
            gl.read_pixels(
                0,
                0,
                self.width as i32,
                self.height as i32,
                glow::RG_INTEGER,
                glow::UNSIGNED_INT,
                glow::PixelPackData::Slice(Some(as_bytes_mut(&mut out))),
            );
            gl.delete_buffer(vbo);
            gl.delete_vertex_array(vertex_array);
        }
        out.chunks_exact(2).map(|p| (p[0], p[1])).collect()
    }

    fn make_current(&self) {
        self.egl
            .make_current(self.display, None, None, Some(self.context))
            .expect("an llvmpipe context made current again");
    }
}

impl Drop for MaskReader {
    fn drop(&mut self) {
        let _ = self.egl.make_current(self.display, None, None, None);
        let _ = self.egl.destroy_context(self.display, self.context);
    }
}

/// A program of a vertex and a fragment shader.
///
/// # Safety
///
/// A GL context must be current.
unsafe fn program(
    gl: &glow::Context,
    vertex: &str,
    fragment: &str,
) -> Result<glow::Program, String> {
    let program = gl.create_program()?;
    for (kind, source) in [
        (glow::VERTEX_SHADER, vertex),
        (glow::FRAGMENT_SHADER, fragment),
    ] {
        let shader = gl.create_shader(kind)?;
        gl.shader_source(shader, source);
        gl.compile_shader(shader);
        if !gl.get_shader_compile_status(shader) {
            return Err(gl.get_shader_info_log(shader));
        }
        gl.attach_shader(program, shader);
    }
    gl.link_program(program);
    if !gl.get_program_link_status(program) {
        return Err(gl.get_program_info_log(program));
    }
    Ok(program)
}

/// The framebuffer (RGBA8 colour, 32-bit float depth), the program and
/// the occlusion query.
///
/// # Safety
///
/// A GL context must be current.
unsafe fn set_up(
    gl: &glow::Context,
    width: u32,
    height: u32,
) -> Result<(glow::Program, glow::UniformLocation, glow::Query), String> {
    let framebuffer = gl.create_framebuffer()?;
    gl.bind_framebuffer(glow::FRAMEBUFFER, Some(framebuffer));
    for (format, attachment) in [
        (glow::RGBA8, glow::COLOR_ATTACHMENT0),
        (glow::DEPTH_COMPONENT32F, glow::DEPTH_ATTACHMENT),
    ] {
        let buffer = gl.create_renderbuffer()?;
        gl.bind_renderbuffer(glow::RENDERBUFFER, Some(buffer));
        gl.renderbuffer_storage(glow::RENDERBUFFER, format, width as i32, height as i32);
        gl.framebuffer_renderbuffer(
            glow::FRAMEBUFFER,
            attachment,
            glow::RENDERBUFFER,
            Some(buffer),
        );
    }
    let status = gl.check_framebuffer_status(glow::FRAMEBUFFER);
    if status != glow::FRAMEBUFFER_COMPLETE {
        return Err(format!("framebuffer incomplete: 0x{status:x}"));
    }
    gl.viewport(0, 0, width as i32, height as i32);
    gl.clear_color(0.0, 0.0, 0.0, 0.0);
    gl.clear_depth_f32(1.0);
    gl.clear(glow::COLOR_BUFFER_BIT | glow::DEPTH_BUFFER_BIT);
    let program = program(
        gl,
        "#version 330 core\n\
             layout(location = 0) in vec3 position;\n\
             layout(location = 1) in float light;\n\
             uniform mat4 transform;\n\
             out float grey;\n\
             void main() { grey = light; gl_Position = transform * vec4(position, 1.0); }\n",
        "#version 330 core\n\
             in float grey;\n\
             out vec4 colour;\n\
             void main() { colour = vec4(grey, grey, grey, 1.0); }\n",
    )?;
    let transform = gl
        .get_uniform_location(program, "transform")
        .ok_or("no uniform `transform`")?;
    let query = gl.create_query()?;
    Ok((program, transform, query))
}

/// The textured program: the position through `transform`, the texture
/// coordinate interpolated perspective-correct, and `texture()` of the
/// sampler on unit 0 (its implicit derivatives and level of detail).
///
/// # Safety
///
/// A GL context must be current.
unsafe fn textured_program(gl: &glow::Context) -> Result<glow::Program, String> {
    program(
        gl,
        "#version 330 core\n\
             layout(location = 0) in vec3 position;\n\
             layout(location = 1) in vec2 uv;\n\
             uniform mat4 transform;\n\
             out vec2 st;\n\
             void main() { st = uv; gl_Position = transform * vec4(position, 1.0); }\n",
        "#version 330 core\n\
             in vec2 st;\n\
             uniform sampler2D image;\n\
             out vec4 colour;\n\
             void main() { colour = texture(image, st); }\n",
    )
}

/// The bytes of a slice of plain numbers, to write into.
#[allow(dead_code)] // the tests read masks; the bench does not
fn as_bytes_mut(values: &mut [u32]) -> &mut [u8] {
    // SAFETY: u32 is plain data; every byte pattern is a valid u32.
    unsafe {
        std::slice::from_raw_parts_mut(values.as_mut_ptr().cast(), std::mem::size_of_val(values))
    }
}

/// The bytes of a slice of plain numbers.
fn as_bytes<T: Copy>(values: &[T]) -> &[u8] {
    // SAFETY: T is u32, f32, Vertex (four f32) or TexturedVertex (five
    // f32), plain data without padding.
    unsafe { std::slice::from_raw_parts(values.as_ptr().cast(), std::mem::size_of_val(values)) }
}
