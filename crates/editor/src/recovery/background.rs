//! Autosave's writer thread (the desktop editor): the document's text is written out and stored
//! off the UI thread, so a large design (a list of millions of numbers: half a second of text)
//! does not stop the window on every edit. The UI hands over a snapshot of the document (cheap:
//! its values are shared) and picks the result up in the frame the thread wakes it for.

use std::sync::Arc;
use std::sync::mpsc::{Receiver, Sender, TryRecvError, channel};

use super::{RecoveryStore, write_pair};

/// Writes a document's text (on the writer thread).
pub type TextJob = Box<dyn FnOnce() -> String + Send>;

/// A write handed to the thread.
struct Job {
    version: u64,
    paths: String,
    text: TextJob,
}

/// What a finished write reports: the document version it wrote, or why it failed.
pub(super) type Finished = (u64, Result<(), String>);

/// The writer thread and whether a write is in flight.
pub(super) struct Background {
    jobs: Sender<Job>,
    done: Receiver<Finished>,
    in_flight: bool,
}

impl Background {
    /// Starts the thread writing into `store`, calling `wake` after each write; `None` when no
    /// thread can be started.
    pub(super) fn start(
        mut store: Box<dyn RecoveryStore + Send>,
        wake: Arc<dyn Fn() + Send + Sync>,
    ) -> Option<Self> {
        let (jobs, inbox) = channel::<Job>();
        let (report, done) = channel();
        std::thread::Builder::new()
            .name("cnets-autosave".into())
            .spawn(move || {
                for job in inbox {
                    let text = (job.text)();
                    let written = write_pair(store.as_mut(), &text, &job.paths);
                    if report
                        .send((job.version, written.map_err(|e| e.to_string())))
                        .is_err()
                    {
                        break;
                    }
                    wake();
                }
            })
            .ok()?;
        Some(Self {
            jobs,
            done,
            in_flight: false,
        })
    }

    /// Whether a write is in flight.
    pub(super) fn busy(&self) -> bool {
        self.in_flight
    }

    /// Hands a write over; `false` when the thread is gone (the caller writes it itself).
    pub(super) fn send(&mut self, version: u64, paths: String, text: TextJob) -> bool {
        let sent = self.jobs.send(Job {
            version,
            paths,
            text,
        });
        self.in_flight = sent.is_ok();
        self.in_flight
    }

    /// The write that finished since the last call, if any.
    pub(super) fn poll(&mut self) -> Option<Finished> {
        if !self.in_flight {
            return None;
        }
        match self.done.try_recv() {
            Ok(finished) => {
                self.in_flight = false;
                Some(finished)
            }
            Err(TryRecvError::Empty) => None,
            Err(TryRecvError::Disconnected) => {
                self.in_flight = false;
                Some((0, Err("the autosave thread stopped".into())))
            }
        }
    }

    /// Waits for the write in flight to finish (before the recovery files are removed: a late
    /// write must not bring them back).
    pub(super) fn wait(&mut self) {
        if std::mem::take(&mut self.in_flight) {
            let _ = self.done.recv();
        }
    }
}
