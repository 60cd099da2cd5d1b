//! PLACEHOLDER: sphere fits.
