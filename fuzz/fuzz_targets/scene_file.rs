//! Scene files, as a student imports or drops them: any bytes. A file that is read must then
//! open in a lab and export again (see `bvhlab_fuzz::accepted`).

#![no_main]

use bvhlab_app::persist::from_file;
use libfuzzer_sys::fuzz_target;

bvhlab_fuzz::same_hash_keys_every_run!();

fuzz_target!(|data: &[u8]| {
    if let Ok(state) = from_file(data) {
        bvhlab_fuzz::accepted(state);
    }
});
