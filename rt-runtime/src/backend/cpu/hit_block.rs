//! A packet's searches handed over (`packet.rs`): each lane's hit to the
//! closest-hit program of its material and ray type, or its miss to the
//! ray type's miss program, as a single trace hands one over
//! (`Lane::handed_to`), but grouped by program: a program with a lane-wise
//! form runs once over all the lanes that go to it, each lane in its own
//! execution context (`rt_std::cpu::lanes::in_block`), so its own traces
//! come out as packets too; one without runs lane by lane. Programs run in
//! the order of their first lane.

use super::bind::Program;
use super::lane::{Lane, Search};
use rt_std::Ray;
use rt_std::cpu::lanes::{LANES, LaneArgs, LanesEntry, Mask, in_block};
use rt_std::cpu::{AnyAttributes, ExecutionContext};
use rt_std::program::CpuLanes;
use std::any::Any;

impl<'a> Lane<'a> {
    /// Hands the searches of `lanes` (`searches[k]` is lane `lanes[k]`'s)
    /// to their programs: see the module's doc.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn hand_over_lanes(
        &self,
        lanes: &[usize],
        searches: &mut [Option<Search<'_>>; LANES],
        rays: &[Ray; LANES],
        payloads: &mut [Option<&mut dyn Any>; LANES],
        flags: u32,
        ray_mask: u32,
        time: f32,
    ) {
        let (depth, outer_time) = self.enter_trace(time);
        // Each lane's program and its call's context, built in place.
        let mut programs: [Option<&'a Program<'a>>; LANES] = [None; LANES];
        let mut contexts: [ExecutionContext<'_>; LANES] = [self.base; LANES];
        let mut attributes: [Option<Box<dyn AnyAttributes>>; LANES] = Default::default();
        for (s, &i) in searches.iter_mut().zip(lanes) {
            let Some(s) = s.as_mut() else { continue };
            // The context is the lane's (its launch index).
            self.enter_block_lane(i);
            attributes[i] = s.attributes.take();
            if let Some((program, ctx)) = self.handed_to(s, &rays[i], flags, ray_mask, &mut attributes[i]) {
                programs[i] = Some(program);
                contexts[i] = ctx;
            }
        }
        // (Only a lane-wise launch traces packets, so a program's lane-wise
        // form is what the context asks for here.)
        for first in 0..LANES {
            let Some(program) = programs[first] else { continue };
            let group: Mask = std::array::from_fn(|l| programs[l].is_some_and(|p| std::ptr::eq(p, program)));
            for (l, _) in group.iter().enumerate().filter(|(_, g)| **g) {
                programs[l] = None;
            }
            match program.desc.cpu_lanes {
                CpuLanes::Lanes(entry) => {
                    self.run_hit_block(entry, program, &group, &mut contexts, &mut attributes, payloads)
                }
                CpuLanes::Scalar(_) => {
                    for l in (0..LANES).filter(|&l| group[l]) {
                        self.enter_block_lane(l);
                        self.invoke(program, &mut contexts[l], payloads[l].as_deref_mut(), attributes[l].as_mut());
                    }
                }
            }
        }
        for a in attributes.into_iter().flatten() {
            self.return_attributes(a);
        }
        self.leave_trace(depth, outer_time);
    }

    /// Runs `program`'s lane-wise `entry` over the lanes of `group`, each
    /// with its call's context (in `contexts`), payload and attributes;
    /// each lane's exception is kept as `invoke` keeps one.
    fn run_hit_block(
        &self,
        entry: LanesEntry,
        program: &Program<'_>,
        group: &Mask,
        contexts: &mut [ExecutionContext<'_>; LANES],
        attributes: &mut [Option<Box<dyn AnyAttributes>>; LANES],
        payloads: &mut [Option<&mut dyn Any>; LANES],
    ) {
        let mut args = LaneArgs::default();
        let lanes = payloads.iter_mut().zip(attributes.iter_mut());
        for (l, (payload, attrs)) in lanes.enumerate().filter(|(l, _)| group[*l]) {
            args.payloads[l] = payload.as_deref_mut();
            args.attributes[l] = attrs.as_mut().map(|a| a.as_any_mut());
        }
        self.store_block_lane();
        let outer = self.program.replace(Some(program.desc));
        in_block(contexts, || entry(group, &mut args, &program.vars));
        self.program.set(outer);
        self.store_block_lane();
        for (l, ctx) in contexts.iter().enumerate().filter(|(l, _)| group[*l]) {
            let first = &self.block.exceptions[l];
            if let Some(code) = ctx.pending_exception
                && first.get().is_none()
            {
                first.set(Some((code, ctx.pending_location)));
            }
        }
    }
}
