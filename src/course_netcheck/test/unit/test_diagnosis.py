from course_netcheck.diagnosis import (ERROR, OK, WARNING, NetworkSettings, diagnose_reachability, diagnose_settings,
                                   has_errors, host_port, parse_ip_addr)

IP_ADDR = """1: lo    inet 127.0.0.1/8 scope host lo\\       valid_lft forever preferred_lft forever
1: lo    inet6 ::1/128 scope host \\       valid_lft forever preferred_lft forever
7: veth0    inet 10.200.0.2/30 scope global veth0\\       valid_lft forever preferred_lft forever
"""
LOCAL = parse_ip_addr(IP_ADDR)


def no_dns(name):
    return {"localhost": ["127.0.0.1"], "robot": ["10.200.0.2"], "far": ["192.0.2.7"]}.get(name, [])


def settings(**kw):
    env = {"ROS_MASTER_URI": "http://10.200.0.1:11311"}
    env.update(kw)
    return NetworkSettings.from_environ(env)


def levels(findings):
    return [f.level for f in findings]


def test_parse_ip_addr():
    assert LOCAL == {"127.0.0.1", "::1", "10.200.0.2"}


def test_host_port():
    assert host_port("http://10.200.0.1:11311/") == ("10.200.0.1", 11311)
    assert host_port("10.200.0.1:11311") is None
    assert host_port("http://master") is None


def test_good_ros_ip():
    findings = diagnose_settings(settings(ROS_IP="10.200.0.2"), LOCAL, no_dns)
    assert levels(findings) == [OK]


def test_ros_ip_not_ours_is_explained():
    findings = diagnose_settings(settings(ROS_IP="10.200.0.9"), LOCAL, no_dns)
    assert has_errors(findings)
    text = str(findings[0])
    assert "ROS_IP=10.200.0.9 is not an address of this host" in text
    assert "10.200.0.2" in text  # tells which addresses would do


def test_ros_ip_must_be_an_address():
    assert "not an IP address" in diagnose_settings(settings(ROS_IP="robot"), LOCAL, no_dns)[0].message


def test_hostname_wins_and_is_checked():
    findings = diagnose_settings(settings(ROS_IP="10.200.0.9", ROS_HOSTNAME="far"), LOCAL, no_dns)
    assert levels(findings) == [WARNING, ERROR]
    assert "resolves to 192.0.2.7" in findings[1].message
    assert "does not resolve" in diagnose_settings(settings(ROS_HOSTNAME="nowhere"), LOCAL, no_dns)[0].message
    assert levels(diagnose_settings(settings(ROS_HOSTNAME="robot"), LOCAL, no_dns)) == [OK]


def test_loopback_with_a_remote_master():
    findings = diagnose_settings(settings(ROS_HOSTNAME="localhost"), LOCAL, no_dns)
    assert has_errors(findings) and "loopback" in findings[0].message
    local_master = NetworkSettings.from_environ({"ROS_MASTER_URI": "http://localhost:11311",
                                                 "ROS_HOSTNAME": "localhost"})
    assert levels(diagnose_settings(local_master, LOCAL, no_dns)) == [OK]


def test_master_uri_missing_or_malformed():
    assert "not set" in diagnose_settings(NetworkSettings(None, "10.200.0.2", None), LOCAL, no_dns)[0].message
    bad = diagnose_settings(settings(ROS_MASTER_URI="10.200.0.1:11311", ROS_IP="10.200.0.2"), LOCAL, no_dns)
    assert "http://HOST:PORT" in bad[0].message


def test_unreachable_master():
    findings = diagnose_reachability("http://10.200.0.1:11311", {}, lambda h, p: False)
    assert levels(findings) == [ERROR] and "cannot reach the master" in findings[0].message


def test_unreachable_node_names_the_node_and_uri():
    reachable = {("10.200.0.1", 11311), ("10.200.0.1", 40000)}
    findings = diagnose_reachability(
        "http://10.200.0.1:11311",
        {"/turtlesim": "http://10.200.0.1:40000/", "/teleop": "http://10.200.0.9:41000/"},
        lambda h, p: (h, p) in reachable)
    assert levels(findings) == [OK, ERROR]
    assert "/teleop registered the URI http://10.200.0.9:41000/" in findings[1].message


def test_all_reachable():
    findings = diagnose_reachability("http://m:1", {"/a": "http://m:2/"}, lambda h, p: True)
    assert levels(findings) == [OK, OK]
