//! The `--report FILE.json` figures: `command`, `version`, `elapsed_s`, `timings`, `io` and
//! each command's own keys.
//!
//! `io`: `read_bytes` (the distinct input files opened, data files named by headers included),
//! `write_bytes` (the files written), and `read_mb_s` / `write_mb_s`: those bytes over the
//! `read` / `write` stage times in MB/s (10⁶ bytes; absent when the stage took no time). The
//! stages include parsing and formatting, so these are the rates a user sees, not the disk's.

use serde_json::{Map, Value};
use std::path::Path;
use std::time::Instant;

/// Collects a command's figures and stage timings.
pub struct Report {
    start: Instant,
    fields: Map<String, Value>,
    timings: Map<String, Value>,
    io: Option<(u64, u64)>,
}

impl Report {
    pub fn new(command: &str) -> Self {
        let mut fields = Map::new();
        fields.insert("command".into(), command.into());
        fields.insert("version".into(), morpho::VERSION.into());
        Report {
            start: Instant::now(),
            fields,
            timings: Map::new(),
            io: None,
        }
    }
    /// Sets a key.
    pub fn set(&mut self, key: &str, v: impl Into<Value>) {
        self.fields.insert(key.to_string(), v.into());
    }
    /// Runs `f`, adding its duration to the stage `stage` (`read`, `compute`, `write`).
    /// On a terminal a spinner shows the stage while it runs (nothing otherwise).
    pub fn time<T>(&mut self, stage: &str, f: impl FnOnce() -> T) -> T {
        let t = Instant::now();
        let bar = spinner(stage);
        let r = f();
        bar.finish_and_clear();
        self.add_time(stage, t.elapsed().as_secs_f64());
        r
    }
    /// Adds `dt` seconds to the stage `stage`.
    pub fn add_time(&mut self, stage: &str, dt: f64) {
        let prev = self
            .timings
            .get(stage)
            .and_then(Value::as_f64)
            .unwrap_or(0.0);
        self.timings.insert(stage.to_string(), (prev + dt).into());
    }
    /// Sets the bytes read and written (`io`; see the module doc).
    pub fn set_io(&mut self, read_bytes: u64, write_bytes: u64) {
        self.io = Some((read_bytes, write_bytes));
    }
    /// The JSON object.
    pub fn to_json(&self) -> Value {
        let mut m = self.fields.clone();
        m.insert(
            "elapsed_s".into(),
            self.start.elapsed().as_secs_f64().into(),
        );
        let mut t = self.timings.clone();
        for k in ["read", "compute", "write"] {
            t.entry(k).or_insert(0.0.into());
        }
        if let Some((r, w)) = self.io {
            let mut io = Map::new();
            for (stage, bytes) in [("read", r), ("write", w)] {
                io.insert(format!("{stage}_bytes"), bytes.into());
                let s = t.get(stage).and_then(Value::as_f64).unwrap_or(0.0);
                if s > 0.0 {
                    io.insert(format!("{stage}_mb_s"), (bytes as f64 / s / 1e6).into());
                }
            }
            m.insert("io".into(), Value::Object(io));
        }
        m.insert("timings".into(), Value::Object(t));
        Value::Object(m)
    }
    /// Writes the report atomically.
    pub fn save(&self, path: &Path) -> morpho::Result<()> {
        let v = self.to_json();
        morpho::io::write_atomic(path, |w| morpho::io::json::write_value_pretty(w, &v))
    }
}

/// A spinner on stderr when it is a terminal; hidden otherwise (CI, pipes, tests).
pub fn spinner(msg: &str) -> indicatif::ProgressBar {
    use std::io::IsTerminal;
    if !std::io::stderr().is_terminal() {
        return indicatif::ProgressBar::hidden();
    }
    let bar = indicatif::ProgressBar::new_spinner();
    bar.set_message(format!("{msg}…"));
    bar.enable_steady_tick(std::time::Duration::from_millis(120));
    bar
}
