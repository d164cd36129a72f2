import threading

from course_graph.plot_buffer import SampleBuffer


def test_series_keep_label_order_and_samples():
    buffer = SampleBuffer(["/a/x", "/a/y"])
    buffer.add("/a/y", 0.5, 2.0)
    buffer.add("/a/x", 0.1, 1.0)
    buffer.add("/a/x", 0.2, 1.5)
    assert buffer.labels == ["/a/x", "/a/y"]
    assert buffer.snapshot() == {"/a/x": ([0.1, 0.2], [1.0, 1.5]), "/a/y": ([0.5], [2.0])}
    assert buffer.count("/a/x") == 2


def test_empty_labels():
    buffer = SampleBuffer(["/a/x", "/a/y"])
    buffer.add("/a/x", 0.0, 1.0)
    assert buffer.empty_labels() == ["/a/y"]


def test_snapshot_is_a_copy():
    buffer = SampleBuffer(["/a/x"])
    buffer.add("/a/x", 0.0, 1.0)
    snapshot = buffer.snapshot()
    buffer.add("/a/x", 1.0, 2.0)
    assert snapshot["/a/x"] == ([0.0], [1.0])


def test_keep_seconds_drops_old_samples():
    buffer = SampleBuffer(["/a/x"], keep_seconds=2.0)
    for t in range(6):
        buffer.add("/a/x", float(t), float(t * 10))
    assert buffer.snapshot()["/a/x"] == ([3.0, 4.0, 5.0], [30.0, 40.0, 50.0])


def test_threads_add_without_losing_samples():
    buffer = SampleBuffer(["/a/x", "/b/y"])

    def add_many(label):
        for i in range(2000):
            buffer.add(label, i * 0.01, float(i))

    threads = [threading.Thread(target=add_many, args=(label,)) for label in ("/a/x", "/b/y", "/a/x")]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    assert buffer.count("/a/x") == 4000 and buffer.count("/b/y") == 2000
