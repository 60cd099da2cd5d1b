//! The lab for assistive technology: egui draws every control on one canvas, which a screen
//! reader cannot see into, so the page keeps a parallel structure of elements, one per node of
//! egui's accessibility tree (AccessKit), with the roles, names and states a screen reader
//! reads, and the keyboard behaviour of native controls.
//!
//! - [`aria`]: which element each node becomes.
//! - [`describe`]: the drawing in words.
//! - [`mirror`]: the page's copy of the tree, and the changes that keep it in step.
//! - [`events`]: what a person does to an element, as the request egui answers.
//! - [`keys`]: which keys the browser keeps, which go on to the lab, and which leave it.
//!
//! The web side (`web/a11y/`) applies the changes to the page and sends back what a person
//! does to the elements (press, focus, a new value) as AccessKit action requests, which egui's
//! widgets answer as they answer a click, so every change still reaches the lab as its
//! model's actions.

pub mod aria;
pub mod describe;
pub mod events;
pub mod keys;
pub mod mirror;
