//! Runs emitted compute shaders on a WebGPU device and times them: wgpu's Vulkan back end, on
//! Mesa's llvmpipe (a conformant software Vulkan device, Debian's `mesa-vulkan-drivers`) where
//! the machine has no GPU. The tests run every emitted model on it, `cargo bench --bench
//! shader_device` times them, and the planner's `cost = "llvmpipe"` times its candidates with
//! it ([`crate::plan`]).
//!
//! # Binding contract
//!
//! A module run here declares
//!
//! ```wgsl
//! // one row per evaluation: `stride` f32 values (wi.xyz, wo.xyz, then h and/or parameters)
//! @group(0) @binding(0) var<storage, read> hair_queries: array<f32>;
//! // three f32 per row (RGB)
//! @group(0) @binding(1) var<storage, read_write> hair_values: array<f32>;
//! // lookup tables, Rgba32Float, read only with textureLoad (never sampled)
//! @group(1) @binding(0) var hair_table_0: texture_2d<f32>;   // 1d/2d/3d; binding 1, 2, ...
//! @compute @workgroup_size(64)
//! fn hair_main(@builtin(global_invocation_id) id: vec3<u32>) {
//!     let row = id.x + id.y * 4194240u;   // ROWS_PER_Y
//!     if row >= arrayLength(&hair_values) / 3u { return; }
//!     ...
//! }
//! ```
//!
//! The compute form of an emitted shader
//! ([`ModelShader::compute`](crate::shader::ModelShader::compute)) follows it, with
//! [`textures_of`] its tables.
//!
//! Rows are dispatched in workgroups of [`WORKGROUP_SIZE`] along x. Up to [`ROWS_PER_Y`]
//! (65535 workgroups, 4 194 240 rows) the dispatch is one-dimensional and `id.y` is 0; beyond,
//! it is `(65535, ceil(groups / 65535), 1)` and the row is `id.x + id.y * ROWS_PER_Y`: a kernel
//! that ignores `id.y` is only correct up to [`ROWS_PER_Y`] rows. Either way the last workgroup
//! overshoots, hence the `arrayLength` test. The values buffer holds exactly three f32 per row
//! and starts as NaN, so a row the kernel does not write reads back as NaN.
//!
//! Group 1 exists only when textures are given: every binding of group 1 the module declares
//! must be given, and every texture given must be declared (the layout is explicit, not
//! derived from the module).
//!
//! All work on one [`Device`] is serialised by a lock, so that a timing is not shared with
//! another thread's dispatch on the same device (other work on the machine still shares the
//! cores: llvmpipe runs on the CPU).

use std::borrow::Cow;
use std::sync::{Mutex, MutexGuard, OnceLock};
use std::time::{Duration, Instant};

use wgpu::util::DeviceExt;
pub use wgpu::{AdapterInfo, TextureDimension};

use crate::shader::ShaderModule;

/// Invocations per workgroup along x, the `@workgroup_size(64)` of the contract.
pub const WORKGROUP_SIZE: u32 = 64;

/// The most workgroups a dispatch has along one dimension (WebGPU's
/// `maxComputeWorkgroupsPerDimension` default, llvmpipe's limit too).
pub const MAX_WORKGROUPS_PER_DIMENSION: u32 = 65535;

/// Rows covered by one step of `id.y`: 65535 workgroups of 64 rows = 4 194 240. A kernel computes
/// its row as `id.x + id.y * 4194240u`.
pub const ROWS_PER_Y: u32 = MAX_WORKGROUPS_PER_DIMENSION * WORKGROUP_SIZE;

/// Why a device could not be created, or a module could not be run on it.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum DeviceError {
    /// No adapter of the kind asked for (no Vulkan driver, or no llvmpipe among them), or the
    /// adapter refused to create a device: wgpu's message.
    #[error("{0}")]
    NoAdapter(String),
    /// Rows, stride, textures or repetitions that do not fit together.
    #[error("{0}")]
    Input(String),
    /// The device rejected the module or a binding (compilation, validation, out of memory):
    /// wgpu's message with its causes.
    #[error("{0}")]
    Rejected(String),
    /// Waiting for a dispatch or reading its values back failed.
    #[error("{0}")]
    Wait(String),
}

/// A lookup table bound in group 1: Rgba32Float texels, `size = [width, height, depth]`
/// (1 for unused dimensions), texels listed with x fastest, then y, then z.
#[derive(Clone, Debug, PartialEq)]
pub struct GpuTexture {
    /// The `@binding` in `@group(1)`.
    pub binding: u32,
    /// Width, height and depth in texels (`[w, 1, 1]` for 1D, `[w, h, 1]` for 2D).
    pub size: [u32; 3],
    /// `D1`, `D2` or `D3`: the WGSL declaration is `texture_1d<f32>`, `texture_2d<f32>` or
    /// `texture_3d<f32>`.
    pub dimension: TextureDimension,
    /// `size[0] * size[1] * size[2]` RGBA texels, x fastest.
    pub texels: Vec<[f32; 4]>,
}

/// The textures of the table bindings of an emitted module, texels from its tables.
pub fn textures_of(module: &ShaderModule) -> Vec<GpuTexture> {
    let tables = module.tables();
    module
        .bindings()
        .iter()
        .map(|b| GpuTexture {
            binding: b.binding,
            size: b.extent(),
            dimension: match b.dimension {
                1 => TextureDimension::D1,
                2 => TextureDimension::D2,
                _ => TextureDimension::D3,
            },
            texels: b.texels(&tables[b.table]),
        })
        .collect()
}

/// Which adapter [`Device::new`] asks wgpu for (Vulkan adapters only).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AdapterChoice {
    /// wgpu's high-performance adapter: a GPU if the machine has one, else llvmpipe.
    HighPerformance,
    /// Mesa's llvmpipe, the software device, even beside a GPU (wgpu's fallback adapter,
    /// whose driver must be llvmpipe).
    Llvmpipe,
}

/// A WebGPU device and its queue, with the adapter it came from.
pub struct Device {
    device: wgpu::Device,
    queue: wgpu::Queue,
    info: AdapterInfo,
    /// Serialises dispatches (and bounds memory: one caller's buffers at a time).
    lock: Mutex<()>,
}

/// Everything a dispatch needs, built once per module and query set.
struct Prepared {
    pipeline: wgpu::ComputePipeline,
    bind_groups: Vec<wgpu::BindGroup>,
    values: wgpu::Buffer,
    rows: u32,
    workgroups: [u32; 2],
}

/// The process's llvmpipe device, created on the first call ([`AdapterChoice::Llvmpipe`]);
/// every later call returns it (or the same error), so that all timings in a process are
/// serialised by one lock.
///
/// # Errors
/// [`DeviceError::NoAdapter`] if the machine has no llvmpipe device.
pub fn llvmpipe() -> Result<&'static Device, DeviceError> {
    static LLVMPIPE: OnceLock<Result<Device, DeviceError>> = OnceLock::new();
    LLVMPIPE
        .get_or_init(|| Device::new(AdapterChoice::Llvmpipe))
        .as_ref()
        .map_err(Clone::clone)
}

impl Device {
    /// Creates a device on the adapter `choice` asks for, with WebGPU's default limits except
    /// the buffer sizes: the adapter's own, so that a million rows of many parameters fit in
    /// one storage binding.
    ///
    /// # Errors
    /// [`DeviceError::NoAdapter`] if there is no such adapter (no Vulkan driver: Debian's
    /// `mesa-vulkan-drivers` provides llvmpipe) or it creates no device.
    pub fn new(choice: AdapterChoice) -> Result<Device, DeviceError> {
        let instance = wgpu::Instance::new(wgpu::InstanceDescriptor {
            backends: wgpu::Backends::VULKAN,
            ..wgpu::InstanceDescriptor::new_without_display_handle()
        });
        let adapter = pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions {
            power_preference: wgpu::PowerPreference::HighPerformance,
            force_fallback_adapter: choice == AdapterChoice::Llvmpipe,
            ..Default::default()
        }))
        .map_err(|error| DeviceError::NoAdapter(error.to_string()))?;
        let info = adapter.get_info();
        if choice == AdapterChoice::Llvmpipe && !is_llvmpipe(&info) {
            return Err(DeviceError::NoAdapter(format!(
                "the software Vulkan adapter is {:?} (driver {:?}), not llvmpipe",
                info.name, info.driver
            )));
        }
        let available = adapter.limits();
        let required_limits = wgpu::Limits {
            max_storage_buffer_binding_size: available.max_storage_buffer_binding_size,
            max_buffer_size: available.max_buffer_size,
            ..wgpu::Limits::default()
        };
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("hairmath"),
            required_limits,
            ..Default::default()
        }))
        .map_err(|error| DeviceError::NoAdapter(error.to_string()))?;
        Ok(Device {
            device,
            queue,
            info,
            lock: Mutex::new(()),
        })
    }

    /// The adapter the device was created from (name, driver, device type).
    pub fn info(&self) -> &AdapterInfo {
        &self.info
    }

    /// The adapter in words: `"llvmpipe (LLVM 15.0.6, 256 bits)" (Cpu, Vulkan), driver
    /// "llvmpipe" "Mesa 22.3.6 (LLVM 15.0.6)"`.
    pub fn describe(&self) -> String {
        let info = &self.info;
        format!(
            "{:?} ({:?}, {:?}), driver {:?} {:?}",
            info.name, info.device_type, info.backend, info.driver, info.driver_info
        )
    }

    /// Runs `f` inside validation, out-of-memory and internal error scopes; the first error
    /// caught becomes [`DeviceError::Rejected`] with its message.
    fn scoped<T>(&self, f: impl FnOnce() -> T) -> Result<T, DeviceError> {
        let scopes = [
            wgpu::ErrorFilter::Validation,
            wgpu::ErrorFilter::OutOfMemory,
            wgpu::ErrorFilter::Internal,
        ]
        .map(|filter| self.device.push_error_scope(filter));
        let value = f();
        let mut first = None;
        for scope in scopes.into_iter().rev() {
            if let Some(error) = pollster::block_on(scope.pop()) {
                first.get_or_insert(error);
            }
        }
        match first {
            None => Ok(value),
            Some(error) => Err(DeviceError::Rejected(describe(&error))),
        }
    }

    /// Takes the device's lock (held until the guard returned is dropped), compiles the
    /// module, uploads the queries (and textures) and builds the bind groups.
    fn prepare(
        &self,
        wgsl: &str,
        entry: &str,
        queries: &[f32],
        stride: usize,
        textures: &[GpuTexture],
    ) -> Result<(MutexGuard<'_, ()>, Prepared), DeviceError> {
        let guard = self
            .lock
            .lock()
            .unwrap_or_else(|poisoned| poisoned.into_inner());
        let input = |message: String| Err(DeviceError::Input(message));
        if stride == 0 {
            return input("stride must be at least 1".into());
        }
        if queries.is_empty() || !queries.len().is_multiple_of(stride) {
            return input(format!(
                "{} query values are not a positive whole number of rows of {stride}",
                queries.len()
            ));
        }
        let Ok(rows) = u32::try_from(queries.len() / stride) else {
            return input(format!("{} rows exceed u32", queries.len() / stride));
        };
        let groups = rows.div_ceil(WORKGROUP_SIZE);
        let workgroups = if groups <= MAX_WORKGROUPS_PER_DIMENSION {
            [groups, 1]
        } else {
            let y = groups.div_ceil(MAX_WORKGROUPS_PER_DIMENSION);
            if y > MAX_WORKGROUPS_PER_DIMENSION {
                return input(format!("{rows} rows need more than 65535^2 workgroups"));
            }
            [MAX_WORKGROUPS_PER_DIMENSION, y]
        };
        for texture in textures {
            let [w, h, d] = texture.size;
            let expected = [w, h, d].map(u64::from).iter().product::<u64>();
            if texture.texels.len() as u64 != expected || expected == 0 {
                return input(format!(
                    "texture at binding {} has {} texels for size {:?}",
                    texture.binding,
                    texture.texels.len(),
                    texture.size
                ));
            }
        }

        let prepared = self.scoped(|| {
            let device = &self.device;
            let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some("hairmath shader"),
                source: wgpu::ShaderSource::Wgsl(Cow::Borrowed(wgsl)),
            });
            let queries_buffer = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("hair_queries"),
                contents: &f32_bytes(queries.iter().copied()),
                usage: wgpu::BufferUsages::STORAGE,
            });
            let values = device.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("hair_values"),
                contents: &f32_bytes((0..rows as usize * 3).map(|_| f32::NAN)),
                usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
            });
            let storage = |binding, read_only| wgpu::BindGroupLayoutEntry {
                binding,
                visibility: wgpu::ShaderStages::COMPUTE,
                ty: wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Storage { read_only },
                    has_dynamic_offset: false,
                    min_binding_size: None,
                },
                count: None,
            };
            let buffers_layout =
                device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                    label: Some("hairmath group 0"),
                    entries: &[storage(0, true), storage(1, false)],
                });
            let buffers_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
                label: Some("hairmath group 0"),
                layout: &buffers_layout,
                entries: &[
                    wgpu::BindGroupEntry {
                        binding: 0,
                        resource: queries_buffer.as_entire_binding(),
                    },
                    wgpu::BindGroupEntry {
                        binding: 1,
                        resource: values.as_entire_binding(),
                    },
                ],
            });
            let mut layouts = vec![buffers_layout];
            let mut bind_groups = vec![buffers_group];
            if !textures.is_empty() {
                let views: Vec<wgpu::TextureView> = textures
                    .iter()
                    .map(|texture| self.upload(texture))
                    .collect();
                let entries: Vec<wgpu::BindGroupLayoutEntry> = textures
                    .iter()
                    .map(|texture| wgpu::BindGroupLayoutEntry {
                        binding: texture.binding,
                        visibility: wgpu::ShaderStages::COMPUTE,
                        ty: wgpu::BindingType::Texture {
                            sample_type: wgpu::TextureSampleType::Float { filterable: false },
                            view_dimension: match texture.dimension {
                                TextureDimension::D1 => wgpu::TextureViewDimension::D1,
                                TextureDimension::D2 => wgpu::TextureViewDimension::D2,
                                TextureDimension::D3 => wgpu::TextureViewDimension::D3,
                            },
                            multisampled: false,
                        },
                        count: None,
                    })
                    .collect();
                let tables_layout =
                    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                        label: Some("hairmath group 1"),
                        entries: &entries,
                    });
                let group_entries: Vec<wgpu::BindGroupEntry> = textures
                    .iter()
                    .zip(&views)
                    .map(|(texture, view)| wgpu::BindGroupEntry {
                        binding: texture.binding,
                        resource: wgpu::BindingResource::TextureView(view),
                    })
                    .collect();
                bind_groups.push(device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some("hairmath group 1"),
                    layout: &tables_layout,
                    entries: &group_entries,
                }));
                layouts.push(tables_layout);
            }
            let layout_refs: Vec<Option<&wgpu::BindGroupLayout>> =
                layouts.iter().map(Some).collect();
            let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: Some("hairmath pipeline layout"),
                bind_group_layouts: &layout_refs,
                immediate_size: 0,
            });
            let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some("hairmath pipeline"),
                layout: Some(&pipeline_layout),
                module: &module,
                entry_point: Some(entry),
                compilation_options: Default::default(),
                cache: None,
            });
            Prepared {
                pipeline,
                bind_groups,
                values,
                rows,
                workgroups,
            }
        })?;
        Ok((guard, prepared))
    }

    /// Creates and fills one Rgba32Float texture; returns its view.
    fn upload(&self, texture: &GpuTexture) -> wgpu::TextureView {
        let [width, height, depth] = texture.size;
        let size = wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: depth,
        };
        let gpu_texture = self.device.create_texture(&wgpu::TextureDescriptor {
            label: Some("hair_table"),
            size,
            mip_level_count: 1,
            sample_count: 1,
            dimension: texture.dimension,
            format: wgpu::TextureFormat::Rgba32Float,
            usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
            view_formats: &[],
        });
        self.queue.write_texture(
            wgpu::TexelCopyTextureInfo {
                texture: &gpu_texture,
                mip_level: 0,
                origin: wgpu::Origin3d::ZERO,
                aspect: wgpu::TextureAspect::All,
            },
            &f32_bytes(texture.texels.iter().flatten().copied()),
            wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(16 * width),
                rows_per_image: Some(height),
            },
            size,
        );
        gpu_texture.create_view(&wgpu::TextureViewDescriptor::default())
    }

    /// Records one dispatch of all rows.
    fn encode_dispatch(&self, prepared: &Prepared, encoder: &mut wgpu::CommandEncoder) {
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("hairmath dispatch"),
            timestamp_writes: None,
        });
        pass.set_pipeline(&prepared.pipeline);
        for (index, group) in prepared.bind_groups.iter().enumerate() {
            pass.set_bind_group(index as u32, group, &[]);
        }
        let [x, y] = prepared.workgroups;
        pass.dispatch_workgroups(x, y, 1);
    }

    /// Submits `commands` and blocks until the device has executed them.
    fn submit_and_wait(&self, commands: wgpu::CommandBuffer) -> Result<(), DeviceError> {
        let index = self.scoped(|| self.queue.submit([commands]))?;
        self.device
            .poll(wgpu::PollType::Wait {
                submission_index: Some(index),
                timeout: None,
            })
            .map(|_| ())
            .map_err(|error| DeviceError::Wait(format!("waiting for the dispatch: {error}")))
    }

    /// Runs the compute entry point `entry` of the WGSL module `wgsl` (to the binding contract)
    /// over the rows of `queries` (`stride` f32 each) with the lookup tables `textures` (group 1,
    /// none if empty), and returns the three f32 of each row: `queries.len() / stride * 3`
    /// values.
    ///
    /// # Errors
    /// [`DeviceError::Input`] for queries that are not whole rows or textures whose texels do
    /// not fill their size; [`DeviceError::Rejected`] with wgpu's message for compilation and
    /// validation errors; [`DeviceError::Wait`] if the device fails to finish or read back.
    pub fn run(
        &self,
        wgsl: &str,
        entry: &str,
        queries: &[f32],
        stride: usize,
        textures: &[GpuTexture],
    ) -> Result<Vec<f32>, DeviceError> {
        let (_guard, prepared) = self.prepare(wgsl, entry, queries, stride, textures)?;
        let bytes = u64::from(prepared.rows) * 3 * 4;
        let (staging, commands) = self.scoped(|| {
            let staging = self.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some("hair_values readback"),
                size: bytes,
                usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            });
            let mut encoder = self
                .device
                .create_command_encoder(&wgpu::CommandEncoderDescriptor::default());
            self.encode_dispatch(&prepared, &mut encoder);
            encoder.copy_buffer_to_buffer(&prepared.values, 0, &staging, 0, bytes);
            (staging, encoder.finish())
        })?;
        self.submit_and_wait(commands)?;

        let wait = |message: String| DeviceError::Wait(message);
        let (sender, receiver) = std::sync::mpsc::channel();
        staging.map_async(wgpu::MapMode::Read, .., move |result| {
            // The receiver waits below; a send error cannot happen.
            let _ = sender.send(result);
        });
        self.device
            .poll(wgpu::PollType::wait_indefinitely())
            .map_err(|error| wait(format!("waiting for the readback: {error}")))?;
        receiver
            .recv()
            .map_err(|error| wait(format!("readback callback: {error}")))?
            .map_err(|error| wait(format!("mapping the readback buffer: {error}")))?;
        let values = staging
            .get_mapped_range(..)
            .map_err(|error| wait(format!("reading the readback buffer: {error}")))?
            .chunks_exact(4)
            .map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
            .collect();
        staging.unmap();
        Ok(values)
    }

    /// Seconds per evaluation of a dispatch of all rows of `queries` (arguments as in
    /// [`Device::run`]): one warm-up dispatch, then the median over `repetitions` dispatches of
    /// the wall-clock time from submit to the completion of `device.poll(wait)`, divided by the
    /// row count. Recording the commands is outside the timed interval; no readback happens.
    ///
    /// # Errors
    /// As [`Device::run`], and [`DeviceError::Input`] for 0 repetitions.
    pub fn time_per_eval(
        &self,
        wgsl: &str,
        entry: &str,
        queries: &[f32],
        stride: usize,
        textures: &[GpuTexture],
        repetitions: usize,
    ) -> Result<f64, DeviceError> {
        if repetitions == 0 {
            return Err(DeviceError::Input(
                "at least one timed repetition is needed".into(),
            ));
        }
        let (_guard, prepared) = self.prepare(wgsl, entry, queries, stride, textures)?;
        let record = || {
            self.scoped(|| {
                let mut encoder = self
                    .device
                    .create_command_encoder(&wgpu::CommandEncoderDescriptor::default());
                self.encode_dispatch(&prepared, &mut encoder);
                encoder.finish()
            })
        };
        self.submit_and_wait(record()?)?;
        let mut times: Vec<Duration> = Vec::with_capacity(repetitions);
        for _ in 0..repetitions {
            let commands = record()?;
            let start = Instant::now();
            self.submit_and_wait(commands)?;
            times.push(start.elapsed());
        }
        times.sort();
        let middle = times.len() / 2;
        let median = if times.len() % 2 == 1 {
            times[middle].as_secs_f64()
        } else {
            (times[middle - 1].as_secs_f64() + times[middle].as_secs_f64()) / 2.0
        };
        Ok(median / f64::from(prepared.rows))
    }
}

/// Whether the adapter is Mesa's llvmpipe (its driver or its name says so).
fn is_llvmpipe(info: &AdapterInfo) -> bool {
    info.driver == "llvmpipe" || info.name.starts_with("llvmpipe")
}

/// wgpu's error with its chain of sources.
fn describe(error: &wgpu::Error) -> String {
    let mut message = error.to_string();
    let mut source = std::error::Error::source(error);
    while let Some(cause) = source {
        let text = cause.to_string();
        if !message.contains(&text) {
            message.push_str("\n  caused by: ");
            message.push_str(&text);
        }
        source = cause.source();
    }
    message
}

/// Little-endian bytes of f32 values (the layout of WGSL's `array<f32>` and of Rgba32Float).
fn f32_bytes(values: impl Iterator<Item = f32>) -> Vec<u8> {
    values.flat_map(f32::to_le_bytes).collect()
}
