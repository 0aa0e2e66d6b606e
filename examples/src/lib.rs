//! The seed's worked examples, and more.
#![allow(clippy::too_many_arguments)]

pub mod common;
pub mod diffuse;
pub mod mesh;
pub mod normal;
pub mod phong;
pub mod scene;
pub mod shadows;
pub mod tutorial;
