//! What the bay screen adds to the live path's publish (issue 32: pages must not slow the live path). The only
//! screen code on that path is zenoh handing each launch the rig worker publishes to the screen's subscriber in
//! the same session (`daemon::bridges::web::feed`: copy the payload, stamp the clock, `try_send` on a bounded
//! queue; everything else runs on the feed's own task). Measured: a put of a real launch (tests/data/web-launch.json)
//! on a zenoh session with no subscriber, and with the screen's feed subscribed; and, for the feed's task, one
//! page message sent on the broadcast channel to 0 and to 20 open pages (each page a task waiting on it).
//! `cargo bench --bench web_feed`

#![allow(clippy::unwrap_used)]

use std::sync::Arc;

use criterion::{criterion_group, criterion_main, Criterion};
use impactd::daemon::bridges::web::feed::{Bay, Feed};
use impactd::daemon::bus::ZenohArgs;
use zenoh::Wait;

const LAUNCH: &[u8] = include_bytes!("../tests/data/web-launch.json");

fn bench(c: &mut Criterion) {
    let rt = tokio::runtime::Builder::new_multi_thread().worker_threads(2).enable_all().build().unwrap();
    // A peer session that listens and connects nowhere (multicast scouting off): local delivery only.
    let session = rt.block_on(ZenohArgs::loopback(vec![], vec![]).open()).unwrap();
    let publisher = session.declare_publisher("golf/rig1/launch").wait().unwrap();
    let mut group = c.benchmark_group("web_feed");
    group.bench_function("put a launch, no screen", |b| b.iter(|| publisher.put(LAUNCH.to_vec()).wait().unwrap()));
    let bay = Bay::new(vec!["rig1".into()], String::new(), Default::default());
    let feed = rt.block_on(Feed::start(&session, bay.clone())).unwrap();
    group.bench_function("put a launch, the screen's feed subscribed", |b| {
        b.iter(|| publisher.put(LAUNCH.to_vec()).wait().unwrap())
    });
    drop(feed);

    // The feed's broadcast of one page message (a shot's JSON text, about 2 KB) to every open page.
    let text: Arc<str> = Arc::from(String::from_utf8_lossy(LAUNCH).as_ref());
    for pages in [0usize, 20] {
        let (tx, _) = tokio::sync::broadcast::channel::<Arc<str>>(256);
        let readers: Vec<_> = (0..pages)
            .map(|_| {
                let mut rx = tx.subscribe();
                rt.spawn(async move {
                    use tokio::sync::broadcast::error::RecvError;
                    while !matches!(rx.recv().await, Err(RecvError::Closed)) {}
                })
            })
            .collect();
        group.bench_function(format!("broadcast a page message to {pages} pages"), |b| {
            b.iter(|| {
                let _ = tx.send(text.clone());
            })
        });
        drop(tx);
        for r in readers {
            r.abort();
        }
    }
    group.finish();
    session.close().wait().unwrap();
}

criterion_group!(benches, bench);
criterion_main!(benches);
