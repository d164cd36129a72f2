"""Suite-wide set-up, before any test starts a process.

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
