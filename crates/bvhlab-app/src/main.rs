//! The lab's entry points: a native window, or the `#lab` canvas of the web page.

#[cfg(not(target_arch = "wasm32"))]
fn main() -> eframe::Result {
    let options = eframe::NativeOptions {
        viewport: egui::ViewportBuilder::default()
            .with_title("bvh-lab")
            .with_inner_size([1280.0, 800.0]),
        ..Default::default()
    };
    eframe::run_native(
        "bvh-lab",
        options,
        Box::new(|_cc| {
            Ok(Box::new(bvhlab_app::native::NativeLab::open(
                bvhlab_app::native::NativeLab::state_path(),
            )))
        }),
    )
}

#[cfg(target_arch = "wasm32")]
fn main() {
    bvhlab_app::web::start();
}
