"""rospy's processes start without ssl, and http.client's HTTPS works as upstream's.

Every rospy process imports xmlrpc.client, hence http.client, whose `import ssl` course_env's
usercustomize answers with a stand-in until HTTPSConnection uses it (docs/rospy_limits.md). Fresh
interpreters, with the hook and without it (course_testkit.python_startup): removing the hook
makes these tests fail.
"""
from __future__ import annotations

import pytest

from course_testkit.python_startup import HOOK_STATE, SETUP, facts, hooked, upstream, without_hook  # noqa: F401

pytestmark = pytest.mark.skipif(not SETUP.exists(), reason="workspace not built")

SSL_STATE = HOOK_STATE + "facts['ssl'] = 'ssl' in sys.modules\n"


@pytest.mark.parametrize("module", ["rospy", "rosgraph.masterapi", "roslaunch", "rosmaster.master", "rostopic"])
def test_rospy_and_its_tools_load_without_ssl(hooked, module):
    got = facts(hooked, "import %s, http.client, urllib.request\n%s" % (module, SSL_STATE))
    assert got["hook_loaded"] and not got["ssl"], "%s loaded ssl" % module
    assert not {"SslDeferral", "UrllibSslDeferral"} & set(got["finders"]), "the finders leave once used"


def test_without_the_hook_ssl_is_loaded(upstream):
    """The control: the same import without the hook's folder loads ssl."""
    got = facts(upstream, "import rospy\n" + SSL_STATE)
    assert got["ssl"] and not got["hook_loaded"]


def test_the_first_https_connection_loads_ssl_into_http_client(hooked):
    got = facts(hooked, """
import http.client
facts['before'] = 'ssl' in sys.modules
connection = http.client.HTTPSConnection('localhost', 1, timeout=1)
import ssl
facts['context'] = isinstance(connection._context, ssl.SSLContext)
facts['swapped'] = http.client.ssl is ssl
try:
    connection.request('GET', '/')
except OSError as error:
    facts['refused'] = type(error).__name__
""")
    assert got == {"before": False, "context": True, "swapped": True, "refused": "ConnectionRefusedError"}


CLIENT_FACTS = """
import http.client, urllib.request
facts['names'] = sorted(n for n in vars(http.client) if not n.startswith('__') and n != 'ssl')
facts['all'] = sorted(http.client.__all__)
facts['https handler'] = hasattr(urllib.request, 'HTTPSHandler')
facts['ssl in urllib'] = urllib.request.ssl.SSLContext is sys.modules['ssl'].SSLContext
"""


def test_the_first_https_request_through_urllib_loads_ssl_into_it(hooked):
    got = facts(hooked, """
import urllib.request
facts['before'] = 'ssl' in sys.modules
try:
    urllib.request.urlopen('https://localhost:1/', timeout=1)
except OSError as error:
    facts['refused'] = type(getattr(error, 'reason', error)).__name__
facts['loaded'] = 'ssl' in sys.modules
context = urllib.request.ssl.create_default_context()
import ssl
facts['swapped'] = urllib.request.ssl is ssl and isinstance(context, ssl.SSLContext)
""")
    assert got == {"before": False, "refused": "ConnectionRefusedError", "loaded": True, "swapped": True}


def test_http_client_and_urllib_look_as_upstream_s(hooked):
    assert facts(hooked, CLIENT_FACTS) == facts(without_hook(hooked), CLIENT_FACTS)


def test_ssl_first_leaves_http_client_as_upstream_has_it(hooked):
    got = facts(hooked, "import ssl, http.client\nfacts['same'] = http.client.ssl is ssl\n" + SSL_STATE)
    assert got["same"] and "SslDeferral" not in got["finders"]
