//! The contract with the compiler's generated thunks: how the CPU backend
//! calls a program's Rust function (its arguments, its result) and binds
//! its variables once per launch.

use core::any::Any;

use crate::Aabb;

/// Arguments for one call of a program on the CPU. The runtime checks at link
/// time that payload, attribute and variable types match the program's
/// declaration; the variables are bound to the program once per launch
/// ([`BoundVariables::bind`]), so a call reads them without a check each.
pub struct CpuArgs<'a> {
    /// The payload (`&mut P`), for programs that take one.
    pub payload: Option<&'a mut dyn Any>,
    /// The attributes (`&A` / `&mut A`), for programs that take them.
    pub attributes: Option<&'a mut dyn Any>,
    /// Primitive index, for intersection and bounding-box programs.
    pub primitive: u32,
    /// Variable values in the program's parameter order, bound by the
    /// program's [`cpu_bind`](crate::program::ProgramDescriptor::cpu_bind)
    /// ([`BoundVariables::NONE`] for a program without variables).
    pub variables: &'a BoundVariables<'a>,
}

/// What a program returned.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum CpuResult {
    /// Most programs return nothing.
    Unit,
    /// A bounding-box program's bounds.
    Aabb(Aabb),
    /// A visit program's chosen child.
    Child(u32),
}

impl From<()> for CpuResult {
    fn from(_: ()) -> Self {
        CpuResult::Unit
    }
}

impl From<Aabb> for CpuResult {
    fn from(b: Aabb) -> Self {
        CpuResult::Aabb(b)
    }
}

impl From<u32> for CpuResult {
    fn from(c: u32) -> Self {
        CpuResult::Child(c)
    }
}

/// Downcasts a program argument; used by generated thunks. `None` when the
/// argument is missing or of another type: a ray traced with a payload type
/// its ray type's programs do not take. The thunk then raises
/// [`EXCEPTION_INVALID_RAY`](crate::EXCEPTION_INVALID_RAY) instead of running
/// the program, as the megakernel does.
#[doc(hidden)]
pub fn __arg<T: 'static>(value: Option<&mut dyn Any>) -> Option<&mut T> {
    value.and_then(|v| v.downcast_mut::<T>())
}

/// Variable values bound to one program's parameter types, once per launch.
///
/// [`bind`](Self::bind) checks each value against the types of a
/// [`VariableList`] (the program's `#[var]` parameter types, in order) and
/// records which list it checked; [`get`](Self::get) compares that record
/// with the list asked for (one comparison, not one downcast per variable)
/// and reads every value. Binding to one list and reading another panics:
/// the values' types are only known to match the list they were bound to.
pub struct BoundVariables<'a> {
    /// The `TypeId` of the [`VariableList`] the values were checked against.
    list: Option<core::any::TypeId>,
    /// One pointer per value, each to a value of its list element's type.
    values: Vec<*const ()>,
    _values: core::marker::PhantomData<&'a (dyn Any + Send + Sync)>,
}

// SAFETY: the pointers come from `&'a (dyn Any + Send + Sync)` references
// (`bind`) and are only read through shared references, so the bound values
// may be shared and sent between threads like those references.
unsafe impl Send for BoundVariables<'_> {}
unsafe impl Sync for BoundVariables<'_> {}

impl core::fmt::Debug for BoundVariables<'_> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("BoundVariables").field("count", &self.values.len()).finish()
    }
}

impl BoundVariables<'static> {
    /// No variables: what a program without `#[var]` parameters is called
    /// with.
    pub const NONE: BoundVariables<'static> =
        BoundVariables { list: None, values: Vec::new(), _values: core::marker::PhantomData };
}

impl<'a> BoundVariables<'a> {
    /// Binds `values` to the types of `L`, in order: an error names the
    /// first value of another type (or the count when they differ).
    pub fn bind<L: VariableList>(values: &[&'a (dyn Any + Send + Sync)]) -> Result<Self, VariableMismatch> {
        let mut next = 0;
        L::check(values, &mut next)?;
        if next != values.len() {
            return Err(VariableMismatch { index: next, expected: "no further variable" });
        }
        Ok(BoundVariables {
            list: Some(core::any::TypeId::of::<L>()),
            values: values.iter().map(|v| (*v as *const (dyn Any + Send + Sync)).cast::<()>()).collect(),
            _values: core::marker::PhantomData,
        })
    }

    /// The values, bound by [`bind::<L>`](Self::bind).
    ///
    /// # Panics
    /// If they were bound to another list (or not at all).
    #[inline]
    pub fn get<L: VariableList>(&self) -> L {
        if self.list != Some(core::any::TypeId::of::<L>()) {
            bound_to_another_list(core::any::type_name::<L>());
        }
        let mut values = self.values.iter();
        // SAFETY: `bind::<L>` checked that the values are, in order, of the
        // types `L::read` reads, and that there are exactly as many.
        unsafe { L::read(&mut values) }
    }
}

#[cold]
#[inline(never)]
fn bound_to_another_list(list: &str) -> ! {
    panic!("variables read as `{list}` were bound to other types (the runtime binds each program's own)")
}

/// A variable value whose type is not the one its program declares.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct VariableMismatch {
    /// Position of the value among the program's variables.
    pub index: usize,
    /// The Rust type the program declares there.
    pub expected: &'static str,
}

impl core::fmt::Display for VariableMismatch {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write!(f, "variable {} is not a `{}`", self.index, self.expected)
    }
}

impl std::error::Error for VariableMismatch {}

/// The types of a program's variables, in order: [`Var<T>`] for one
/// variable of type `T`, and tuples (nested as deep as needed) of those.
/// Generated thunks name it; [`BoundVariables`] checks and reads it.
///
/// # Safety
/// `read` reads exactly the values, and as the types, that `check`
/// accepted.
pub unsafe trait VariableList: Copy + 'static {
    /// Checks `values[*next..]` against the list's types, advancing `next`
    /// past them.
    fn check(values: &[&(dyn Any + Send + Sync)], next: &mut usize) -> Result<(), VariableMismatch>;
    /// Reads the list's values.
    ///
    /// # Safety
    /// `values` yields pointers to values of the types `check` accepted, in
    /// its order.
    unsafe fn read(values: &mut core::slice::Iter<'_, *const ()>) -> Self;
}

/// One variable of type `T` in a [`VariableList`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Var<T>(pub T);

// SAFETY: `read` reads one `T`, which `check` verified.
unsafe impl<T: Copy + 'static> VariableList for Var<T> {
    #[inline]
    fn check(values: &[&(dyn Any + Send + Sync)], next: &mut usize) -> Result<(), VariableMismatch> {
        let expected = core::any::type_name::<T>();
        match values.get(*next) {
            Some(v) if v.is::<T>() => {
                *next += 1;
                Ok(())
            }
            _ => Err(VariableMismatch { index: *next, expected }),
        }
    }

    #[inline(always)]
    unsafe fn read(values: &mut core::slice::Iter<'_, *const ()>) -> Self {
        // SAFETY: see the trait: the next pointer is to a live `T`.
        unsafe { Var(*values.next().unwrap_unchecked().cast::<T>()) }
    }
}

macro_rules! variable_tuples {
    ($(($($t:ident),*)),* $(,)?) => {$(
        // SAFETY: `read` reads the elements in `check`'s order.
        unsafe impl<$($t: VariableList),*> VariableList for ($($t,)*) {
            #[inline]
            #[allow(unused_variables)]
            fn check(values: &[&(dyn Any + Send + Sync)], next: &mut usize) -> Result<(), VariableMismatch> {
                $($t::check(values, next)?;)*
                Ok(())
            }

            #[inline(always)]
            #[allow(unused_variables, unused_unsafe, clippy::unused_unit)]
            unsafe fn read(values: &mut core::slice::Iter<'_, *const ()>) -> Self {
                // SAFETY: as the trait says, element by element.
                unsafe { ($($t::read(values),)*) }
            }
        }
    )*};
}

variable_tuples!(
    (),
    (A),
    (A, B),
    (A, B, C),
    (A, B, C, D),
    (A, B, C, D, E),
    (A, B, C, D, E, F),
    (A, B, C, D, E, F, G),
    (A, B, C, D, E, F, G, H),
);
