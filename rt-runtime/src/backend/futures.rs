//! Waiting for the device without blocking. The launch path is written as
//! futures, so that a browser page (wasm32 over WebGPU), whose one thread
//! must never block, can await a launch
//! ([`crate::Context::launch_async`]); the blocking API runs the same
//! futures to the end ([`now`]). Natively a wait inside them first polls
//! the device until it is idle (`wgpu::Device::poll`), after which what it
//! waits for has happened, so [`now`] never parks the thread for long.

use std::future::Future;
use std::pin::Pin;
use std::sync::{Arc, Mutex};
use std::task::{Context, Poll, Waker};

/// A boxed future that need not be `Send` (a launch borrows the scene).
pub(crate) type LocalBoxFuture<'a, T> = Pin<Box<dyn Future<Output = T> + 'a>>;

/// Runs `f` to its end: natively by blocking (pollster); in a browser,
/// where nothing may block, only if it ends without waiting (`None` when
/// it would have to wait for the device).
pub(crate) fn now<F: Future>(f: F) -> Option<F::Output> {
    #[cfg(not(target_arch = "wasm32"))]
    {
        Some(pollster::block_on(f))
    }
    #[cfg(target_arch = "wasm32")]
    {
        let mut f = std::pin::pin!(f);
        match f.as_mut().poll(&mut Context::from_waker(Waker::noop())) {
            Poll::Ready(v) => Some(v),
            Poll::Pending => None,
        }
    }
}

/// A blocking call of a fallible future: [`now`], failing in a browser
/// with [`DeviceError::WouldBlock`](crate::error::DeviceError::WouldBlock) where it
/// would have to wait for the device.
pub(crate) fn block<T>(f: impl Future<Output = crate::error::Result<T>>) -> crate::error::Result<T> {
    now(f).unwrap_or(Err(crate::error::DeviceError::WouldBlock.into()))
}

/// A value a callback delivers once (a buffer's mapping), to be awaited.
pub(crate) struct Delivery<T> {
    shared: Arc<Mutex<(Option<T>, Option<Waker>)>>,
}

impl<T> Delivery<T> {
    /// The delivery, and what the callback calls with the value.
    pub(crate) fn new() -> (Delivery<T>, impl FnOnce(T) + Send + 'static)
    where
        T: Send + 'static,
    {
        let shared = Arc::new(Mutex::new((None, None::<Waker>)));
        let sender = Arc::clone(&shared);
        let deliver = move |value: T| {
            let mut slot = sender.lock().unwrap_or_else(|e| e.into_inner());
            slot.0 = Some(value);
            if let Some(waker) = slot.1.take() {
                waker.wake();
            }
        };
        (Delivery { shared }, deliver)
    }

    /// The value, if it came.
    pub(crate) fn take(&self) -> Option<T> {
        self.shared.lock().unwrap_or_else(|e| e.into_inner()).0.take()
    }
}

impl<T> Future for Delivery<T> {
    type Output = T;
    fn poll(self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<T> {
        let mut slot = self.shared.lock().unwrap_or_else(|e| e.into_inner());
        match slot.0.take() {
            Some(v) => Poll::Ready(v),
            None => {
                slot.1 = Some(cx.waker().clone());
                Poll::Pending
            }
        }
    }
}

/// `inner` with a panic in any of its polls caught
/// ([`crate::panics::catching`]) and returned instead of unwinding.
pub(crate) struct Catching<'a, T>(pub LocalBoxFuture<'a, T>);

impl<T> Future for Catching<'_, T> {
    type Output = Result<T, crate::panics::Caught>;
    fn poll(mut self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<Self::Output> {
        match crate::panics::catching(|| self.0.as_mut().poll(cx)) {
            Ok(Poll::Ready(v)) => Poll::Ready(Ok(v)),
            Ok(Poll::Pending) => Poll::Pending,
            Err(caught) => Poll::Ready(Err(caught)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_delivery_awaits_its_callback() {
        let (delivery, deliver) = Delivery::new();
        std::thread::spawn(move || deliver(7u32));
        assert_eq!(now(delivery), Some(7));
    }

    #[test]
    fn a_panic_in_a_poll_is_caught() {
        let f: LocalBoxFuture<'_, u32> = Box::pin(async { panic!("in a future") });
        let caught = now(Catching(f)).unwrap().unwrap_err();
        assert_eq!(caught.message, "in a future");
    }
}
