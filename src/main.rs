//! The `veneer` command line: thin wrappers over the library (see `cli/`).

mod cli;

fn main() -> std::process::ExitCode {
    see_mesa_float_render_targets();
    cli::run()
}

/// On Mesa's desktop OpenGL, wgpu finds float render targets only by extension names
/// that Mesa's core profiles leave out (gfx-rs/wgpu#2838), so materials with float
/// buffers would be refused on a machine whose only adapter is GL. Naming the extension
/// (the driver has what it stands for: float colour buffers are core since GL 3.0) lets
/// wgpu see them; other drivers ignore the variable, and a value the user set is kept.
fn see_mesa_float_render_targets() {
    const VARIABLE: &str = "MESA_EXTENSION_OVERRIDE";
    if std::env::var_os(VARIABLE).is_none() {
        // SAFETY: the first thing `main` does, before any other thread exists.
        unsafe { std::env::set_var(VARIABLE, "+GL_ARB_color_buffer_float") };
    }
}
