//! Variables set by name on scopes (OptiX's `rtVariableSet*` on a
//! context, program, geometry, instance, material or node).

use super::Context;
use crate::error::Result;
use crate::scene::Scope;
use crate::vars::IntoVariable;

impl Context {
    /// Sets variable `name` on `scope`. Values are plain data (`f32`,
    /// `Vec3`, `#[rt_struct]`s), buffers, samplers or nodes. Changing a value
    /// never relinks.
    pub fn set_var(&mut self, scope: impl Into<Scope>, name: &str, value: impl IntoVariable) -> Result<()> {
        let value = value.into_variable();
        self.scene.scope_mut(scope.into())?.set(name, value);
        Ok(())
    }

    /// Removes variable `name` from `scope`; returns whether it was set.
    pub fn remove_var(&mut self, scope: impl Into<Scope>, name: &str) -> Result<bool> {
        Ok(self.scene.scope_mut(scope.into())?.remove(name).is_some())
    }
}
