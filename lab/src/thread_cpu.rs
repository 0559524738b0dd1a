//! The calling thread's CPU time (`CLOCK_THREAD_CPUTIME_ID`), for
//! benchmarks that time CPU work on a machine shared with other work: a
//! wall clock also counts the time the thread waited while another thread
//! (the software rasterizer's workers, a build) had the core, which on a
//! busy two-core machine moved `npr bench host`'s medians by half.

use std::time::Duration;

/// CPU time the calling thread has used so far.
pub fn now() -> Duration {
    let t = rustix::time::clock_gettime(rustix::time::ClockId::ThreadCPUTime);
    Duration::new(t.tv_sec as u64, t.tv_nsec as u32)
}

/// Microseconds of CPU time `f` used on this thread, and its result.
pub fn time_us<T>(f: impl FnOnce() -> T) -> (f64, T) {
    let start = now();
    let out = f();
    ((now() - start).as_secs_f64() * 1e6, out)
}

#[cfg(test)]
mod tests {
    #[test]
    fn busy_work_takes_cpu_time_and_sleep_does_not() {
        let (busy, sum) =
            super::time_us(|| (0..20_000_000u64).fold(0u64, |a, i| a.wrapping_add(std::hint::black_box(i) * i)));
        assert!(sum > 0);
        assert!(busy > 1000.0, "20M multiply-adds took {busy} µs of CPU");
        let (slept, ()) = super::time_us(|| std::thread::sleep(std::time::Duration::from_millis(50)));
        assert!(slept < 10_000.0, "a 50 ms sleep used {slept} µs of CPU");
    }
}
