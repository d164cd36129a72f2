"""Suite-wide set-up: signals before any test starts a process, and early starts.

A suite started in the background (`nohup make test &`, a CI runner's job) may inherit SIGINT as
*ignored*: a non-interactive shell ignores it for background commands, and an ignored signal
stays ignored through exec. Every node the tests start would then ignore the Ctrl-C that stops
it and sit out its kill timeout (a 0.5 s test took 25 s). Take SIGINT back, as a terminal gives
it: Python's KeyboardInterrupt here, the default action in the processes the tests start."""
import signal

if signal.getsignal(signal.SIGINT) is signal.SIG_IGN:
    signal.signal(signal.SIGINT, signal.default_int_handler)
if signal.getsignal(signal.SIGQUIT) is signal.SIG_IGN:
    signal.signal(signal.SIGQUIT, signal.SIG_DFL)


def starts_early(item) -> bool:
    return hasattr(getattr(item, "module", None), "start_early")


def pytest_collection_modifyitems(items) -> None:
    """The tests of a module with `start_early(config)` run last, so that its background work
    has the whole suite to overlap (the order within each part is kept)."""
    items.sort(key=starts_early)


def pytest_collection_finish(session) -> None:
    """A selected test module with `start_early(config)` starts its slow background work now
    (tests/test_grader_samples.py grades its samples)."""
    if session.config.option.collectonly:
        return
    modules = {item.module for item in session.items if starts_early(item)}
    for module in sorted(modules, key=lambda m: m.__name__):
        module.start_early(session.config)
