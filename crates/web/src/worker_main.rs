//! The workers' entry point (wasm32 only): `worker.js` instantiates the page's own wasm module in
//! a Web Worker and calls [`worker_start`], which answers the page's messages with a [`Service`]
//! (the evaluation worker) or a [`DragService`] (the drag worker: the same module, started by
//! the page's first drag of the net; each solve answered as it arrives).
//!
//! Latest change wins: a message only files the newest request; the evaluation loop takes it
//! when it is free. After a request's first phase (the 3D view's answer) the loop waits for a
//! newer request — while the page's pointer is held, until it is released; otherwise up to
//! 300 ms — and when one comes, the rest of the stale one is dropped, so a drag's pictures never
//! wait for a slow node that is not previewed.

use std::cell::RefCell;
use std::rc::Rc;
use std::sync::Arc;

use wasm_bindgen::JsCast as _;
use wasm_bindgen::prelude::*;
use web_sys::{DedicatedWorkerGlobalScope, MessageEvent};

use crate::drag_service::DragService;
use crate::service::Service;
use crate::wire::{self, Job, ToWorker};

/// The newest request not yet taken, and whether the evaluation loop is running.
#[derive(Default)]
struct Inbox {
    newest: Option<Job>,
    running: bool,
    /// The page released the pointer held during the last request (its rest may run).
    released: bool,
}

fn scope() -> DedicatedWorkerGlobalScope {
    js_sys::global().unchecked_into()
}

/// Sends a message to the page (its bytes are transferred, not copied).
fn post(bytes: &[u8]) {
    let array = js_sys::Uint8Array::from(bytes);
    let transfer = js_sys::Array::of1(&array.buffer());
    if let Err(e) = scope().post_message_with_transfer(&array, &transfer) {
        web_sys::console::warn_2(&"cnets worker: cannot answer the page".into(), &e);
    }
}

/// Starts answering the page (called by `worker.js` once the module is instantiated).
#[wasm_bindgen]
pub fn worker_start() {
    std::panic::set_hook(Box::new(|info| {
        // wasm has no unwinding: the instance stops here. The page restarts the worker.
        let text = info.to_string();
        web_sys::console::error_1(&format!("cnets worker: {text}").into());
        post(&wire::encode_stopped(&text));
    }));
    crate::bundle::provide_all();
    let registry = Arc::new(cnets_nodes::registry());
    let service = Rc::new(RefCell::new(Service::new(registry.clone())));
    let drag = Rc::new(RefCell::new(DragService::new(registry)));
    let inbox = Rc::new(RefCell::new(Inbox::default()));
    let on_message = Closure::<dyn FnMut(MessageEvent)>::new(move |event: MessageEvent| {
        let bytes = js_sys::Uint8Array::new(&event.data()).to_vec();
        match wire::decode_to_worker(&bytes) {
            Ok(ToWorker::Provide { name, bytes }) => {
                cnets_engine::files::memory::provide(&name, bytes);
            }
            Ok(ToWorker::Literal { key, value }) => service.borrow_mut().remember(key, value),
            Ok(ToWorker::Parse(job)) => post(&service.borrow_mut().parse(job)),
            Ok(ToWorker::Released) => inbox.borrow_mut().released = true,
            Ok(ToWorker::DragStart(job)) => drag.borrow_mut().start(&job),
            Ok(ToWorker::DragAim { target, steps }) => post(&drag.borrow_mut().aim(target, steps)),
            Ok(ToWorker::Evaluate(job)) => {
                // Forgotten on receipt: a request still waiting is replaced by this one, and the
                // one running holds its values already.
                service.borrow_mut().forget(&job.forget);
                let start = {
                    let mut inbox = inbox.borrow_mut();
                    inbox.released = false;
                    inbox.newest = Some(job);
                    !std::mem::replace(&mut inbox.running, true)
                };
                if start {
                    wasm_bindgen_futures::spawn_local(run(inbox.clone(), service.clone()));
                }
            }
            Err(e) => web_sys::console::warn_1(&format!("cnets worker: {e}").into()),
        }
    });
    scope().set_onmessage(Some(on_message.as_ref().unchecked_ref()));
    // The handler lives as long as the worker.
    on_message.forget();
    post(&wire::encode_ready());
}

/// The evaluation loop: answers the newest request until there is none.
async fn run(inbox: Rc<RefCell<Inbox>>, service: Rc<RefCell<Service>>) {
    loop {
        // Let the messages queued during the last evaluation in: only the newest request runs.
        yield_now().await;
        let Some(job) = inbox.borrow_mut().newest.take() else {
            inbox.borrow_mut().running = false;
            return;
        };
        let held = job.held;
        let (messages, rest) = service.borrow_mut().begin(job);
        messages.iter().for_each(|m| post(m));
        let Some(rest) = rest else { continue };
        // The rest (the nodes not previewed: a nest, the exports) can take seconds, and the
        // worker sees no newer request while it runs: during a drag it would hold every later
        // picture back. So it waits for a newer request first — while the page's pointer is
        // held (a drag), until it is released; otherwise a moment — and a newer request makes
        // this one stale: its rest never runs.
        let mut waited = 0;
        let stale = loop {
            sleep_ms(REST_WAIT_STEP_MS).await;
            waited += REST_WAIT_STEP_MS;
            let inbox = inbox.borrow();
            if inbox.newest.is_some() {
                break true;
            }
            let due = if held {
                inbox.released || waited >= HELD_REST_LIMIT_MS
            } else {
                waited >= REST_GRACE_MS
            };
            if due {
                break false;
            }
        };
        if stale {
            continue;
        }
        let messages = service.borrow_mut().finish(rest);
        messages.iter().for_each(|m| post(m));
    }
}

/// How long a request's rest waits for a newer request after its first phase (milliseconds),
/// looking every [`REST_WAIT_STEP_MS`]; a request made while the pointer was held waits for its
/// release instead, at most [`HELD_REST_LIMIT_MS`] (a press held still).
const REST_GRACE_MS: i32 = 300;
const REST_WAIT_STEP_MS: i32 = 25;
const HELD_REST_LIMIT_MS: i32 = 10_000;

/// Returns to the worker's event loop once (its queued messages are delivered meanwhile).
async fn yield_now() {
    sleep_ms(0).await;
}

/// Returns to the worker's event loop for `ms` milliseconds.
async fn sleep_ms(ms: i32) {
    let promise = js_sys::Promise::new(&mut |resolve, _| {
        let _ = scope().set_timeout_with_callback_and_timeout_and_arguments_0(&resolve, ms);
    });
    let _ = wasm_bindgen_futures::JsFuture::from(promise).await;
}
