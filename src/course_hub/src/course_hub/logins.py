"""Failed logins, counted per user name and per address, so that guessing passwords is slow.

A name with `per_name` failures within the last `window_s` seconds, or an address with
`per_address`, is refused without its password being looked at (which costs the hub a bcrypt
hash) until its oldest failure in the window has aged out. The address's bound is the larger: a
class behind one NAT address mistypes together. A successful login forgets its name's failures,
not its address's. Memory stays bounded: failures older than the window are dropped; names are
counted only for the hub's users (a bounded set); past `max_keys` addresses, those whose last
failure is oldest are forgotten first (never a name: flooding from many addresses cannot wipe a
name's count).

Plain logic with an injectable clock (course_hub.auth wires it into JupyterHub's login).
"""
from __future__ import annotations

import collections
import time
from typing import Callable, Deque, Dict, Optional, Tuple

Key = Tuple[str, str]  # ("name", alice) or ("address", 10.0.0.7)


class FailedLogins:
    def __init__(self, per_name: int = 5, per_address: int = 50, window_s: float = 300.0,
                 max_keys: int = 10000, clock: Callable[[], float] = time.monotonic) -> None:
        if per_name < 1 or per_address < 1 or window_s <= 0 or max_keys < 2:
            raise ValueError("the limits must be positive")
        self.per_name, self.per_address, self.window_s = per_name, per_address, window_s
        self.max_keys = max_keys
        self.clock = clock
        self._failures: Dict[Key, Deque[float]] = {}

    def _recent(self, key: Key, now: float) -> Deque[float]:
        times = self._failures.get(key)
        if times is None:
            return collections.deque()
        while times and times[0] <= now - self.window_s:
            times.popleft()
        if not times:
            del self._failures[key]
        return times

    def refusal(self, name: str, address: str) -> Optional[Tuple[str, float]]:
        """None when a login as `name` from `address` may be tried now; else what refuses it
        ("name" or "address") and the seconds until it may be tried."""
        now = self.clock()
        for key, bound in ((("name", name), self.per_name), (("address", address), self.per_address)):
            times = self._recent(key, now)
            if len(times) >= bound:
                return key[0], times[len(times) - bound] + self.window_s - now
        return None

    def failed(self, name: Optional[str], address: str) -> None:
        """Count a failed login from `address`, as `name` when the name is a user of the hub (an
        unknown name is counted against its address only: it cannot be guessed into)."""
        now = self.clock()
        keys = [("address", address)] + ([("name", name)] if name is not None else [])
        for key in keys:
            times = self._recent(key, now)
            times.append(now)
            bound = self.per_name if key[0] == "name" else self.per_address
            while len(times) > bound:  # only the last `bound` failures decide
                times.popleft()
            self._failures[key] = times
        self._forget_oldest()

    def succeeded(self, name: str) -> None:
        self._failures.pop(("name", name), None)

    def _forget_oldest(self) -> None:
        if self.addresses() <= self.max_keys:
            return
        now = self.clock()
        for key in list(self._failures):
            self._recent(key, now)
        addresses = [key for key in self._failures if key[0] == "address"]
        excess = len(addresses) - self.max_keys
        if excess > 0:
            for key in sorted(addresses, key=lambda k: self._failures[k][-1])[:excess]:
                del self._failures[key]

    def addresses(self) -> int:
        """How many addresses have failures on record."""
        return sum(1 for key in self._failures if key[0] == "address")
