//! The workers' entry point (wasm32 only): `worker.js` instantiates the page's own wasm module in
//! a Web Worker and calls [`worker_start`], which answers the page's messages with a [`Service`]
//! (the evaluation worker) or a [`DragService`] (the drag worker: the same module, started by
//! the page's first drag of the net; each solve answered as it arrives).
//!
//! Latest change wins: a message only files the newest request; the evaluation loop takes it
//! when it is free. After a request's first phase (the 3D view's answer) the loop lets the
//! worker's queued messages in; when a newer request came meanwhile, the rest of the stale one
//! is dropped.

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
            Ok(ToWorker::DragStart(job)) => drag.borrow_mut().start(&job),
            Ok(ToWorker::DragAim { target, steps }) => post(&drag.borrow_mut().aim(target, steps)),
            Ok(ToWorker::Evaluate(job)) => {
                // Forgotten on receipt: a request still waiting is replaced by this one, and the
                // one running holds its values already.
                service.borrow_mut().forget(&job.forget);
                let start = {
                    let mut inbox = inbox.borrow_mut();
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
        let (messages, rest) = service.borrow_mut().begin(job);
        messages.iter().for_each(|m| post(m));
        let Some(rest) = rest else { continue };
        yield_now().await;
        if inbox.borrow().newest.is_some() {
            // Stale: a newer request came while the 3D view was answered; its rest never runs.
            continue;
        }
        let messages = service.borrow_mut().finish(rest);
        messages.iter().for_each(|m| post(m));
    }
}

/// Returns to the worker's event loop once (its queued messages are delivered meanwhile).
async fn yield_now() {
    let promise = js_sys::Promise::new(&mut |resolve, _| {
        let _ = scope().set_timeout_with_callback_and_timeout_and_arguments_0(&resolve, 0);
    });
    let _ = wasm_bindgen_futures::JsFuture::from(promise).await;
}
