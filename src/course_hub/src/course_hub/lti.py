"""CourseLTIAuthenticator: the hub's login from the LMS (an LTI 1.3 launch), built on JupyterHub's
own jupyterhub-ltiauthenticator and configured by traits, beside CourseAuthenticator (a class
chooses one: deploy/jupyterhub/jupyterhub_config.py, HUB_AUTH=lti):

    c.JupyterHub.authenticator_class = "course_hub.lti.CourseLTIAuthenticator"  # or its entry point, "course-lti"
    c.CourseLTIAuthenticator.issuer = "https://canvas.instructure.com"           # the platform's iss
    c.CourseLTIAuthenticator.client_id = {"10000000000042"}                      # the tool's client id(s) there
    c.CourseLTIAuthenticator.deployment_ids = {"42:8865aa05b4b79b64a91a86042e43af5ea8ae79eb"}
    c.CourseLTIAuthenticator.authorize_url = "https://sso.canvaslms.com/api/lti/authorize_redirect"
    c.CourseLTIAuthenticator.jwks_endpoint = "https://sso.canvaslms.com/api/lti/security/jwks"
    c.CourseLTIAuthenticator.data_dir = "/var/lib/ros-course-hub"

The launch: the LMS posts the third-party login to `/hub/lti13/oauth_login`, the hub sends the
browser to the platform's `authorize_url` with a state and a nonce (each also in a cookie), and
the platform posts a signed id_token back to `/hub/lti13/oauth_callback`. What the course adds
to ltiauthenticator's checks (state cookie, signature against the platform's JWKS, aud, iss,
exp, iat at most 10 min old, the LTI claims, nonce cookie):

- **the deployment** must be one of `deployment_ids` (ltiauthenticator takes any), and the login
  start's `iss` and `client_id` this class's platform and tool;
- **replays refused:** each state and nonce is accepted once (course_hub.lms.UsedOnce): a launch
  posted again with its cookies is refused;
- **the role decides the hub's** (course_hub.lms.role_of): Instructor or TeachingAssistant makes
  a TA, a hub admin for the class; Learner a student; no role claim is refused;
- **the name** comes from a claim that never changes (`username_key`: `sub` by default, or a
  custom parameter such as `custom_login_id`; no fallback to another claim), through the hub's
  name rules (course_hub.lms.hub_name, course_hub.names); a second LMS user whose name maps onto
  one another holds is refused, never merged (`<data_dir>/lti-users.json`, which the grades back
  to the LMS read too);
- **the milestone**: a launch whose custom parameter `milestone` names one (checked against the
  milestone ids' pattern) lands on the student's workbench opened on it (`milestone_path`
  under `/hub/user-redirect/`, through `/hub/spawn`, which starts the server first if needed);
- **the JWKS** fetched by one cached client, beside the event loop (ltiauthenticator fetches it
  on the loop at every launch).

Every refusal answers 4xx with `LTI launch refused: <why>` on JupyterHub's error page and one
warning line in the hub's log, before any user exists; none creates a user or a server.
"""
from __future__ import annotations

import asyncio
from concurrent.futures import ThreadPoolExecutor
from typing import Any, Dict, NoReturn, Optional
from urllib.parse import quote

import jwt
from jupyterhub.utils import url_path_join
from ltiauthenticator.lti13.auth import LTI13Authenticator
from ltiauthenticator.lti13.error import InvalidAudienceError, TokenError, ValidationError
from ltiauthenticator.lti13.handlers import LTI13CallbackHandler, LTI13LoginInitHandler, _deserialize_state
from ltiauthenticator.lti13.validator import LTI13LaunchValidator
from ltiauthenticator.utils import convert_request_to_dict
from tornado import web
from traitlets import Integer, List as ListTrait, Set, Unicode, default

from course_hub import defaults, lms

REQUIRED = ("issuer", "client_id", "deployment_ids", "authorize_url", "jwks_endpoint")
# the id_token's claims PyJWT must find (LTI 1.3's own, and sub: the hub names users by it)
REQUIRED_CLAIMS = ["exp", "iat", "iss", "aud", "sub", "nonce"]
JWKS_TIMEOUT_S = 10


def refuse(handler: web.RequestHandler, status: int, why: str) -> NoReturn:
    """Log why a launch was refused (a warning with the caller's address) and answer `status`
    with `LTI launch refused: why` (JupyterHub's error page shows it)."""
    handler.log.warning("LTI launch refused (%s %s from %s): %s", handler.request.method, handler.request.path,
                        handler.request.remote_ip, why)
    raise web.HTTPError(status, "LTI launch refused: %s", why)


class CourseLTILoginHandler(LTI13LoginInitHandler):
    """`/hub/lti13/oauth_login`, the third-party login's start: ltiauthenticator's, refusing a
    platform or tool that is not this class's before the browser goes anywhere."""

    def post(self) -> None:
        auth: CourseLTIAuthenticator = self.authenticator
        iss = self.get_argument("iss", "")
        if iss != auth.issuer:
            refuse(self, 400, "the launch comes from the platform %r, which is not this class's LMS (%s)"
                   % (iss[:200], auth.issuer))
        client_id = self.get_argument("client_id", "")
        if client_id and client_id not in auth.client_id:
            refuse(self, 400, "the launch is for the tool %r, which is not this hub's client id in the LMS"
                   % client_id[:200])
        super().post()

    get = post

    def _set_oauth_cookie(self, key: str, value: str) -> None:
        """The state's and nonce's cookies, which the platform's form_post brings back from another
        site: SameSite=None (a browser keeps Lax cookies off a cross-site POST, and the launch
        would fail with "OAuth state missing from cookies"), so Secure, which browsers allow on
        https and on loopback names alone."""
        self._set_cookie(key, value, expires_days=1, httponly=True, encrypted=True, samesite="None", secure=True)


class CourseLTICallbackHandler(LTI13CallbackHandler):
    """`/hub/lti13/oauth_callback`, where the platform posts the id_token (module docstring)."""

    async def post(self) -> None:
        claims = await self.validated_claims()
        try:
            milestone = lms.milestone_of(claims, self.authenticator.milestone_parameter)
        except lms.Refused as err:
            refuse(self, 400, str(err))
        user = await self.login_user(claims)  # CourseLTIAuthenticator.authenticate refuses with 403
        if user is None:
            refuse(self, 403, "the hub does not let this user in (blocked, or not allowed by the hub's configuration)")
        self.redirect(self.landing(user, milestone))

    def landing(self, user: Any, milestone: Optional[str]) -> str:
        """Where the launch's browser goes: the workbench opened on `milestone` (through
        /hub/spawn, which starts the server first when it is not running), else the state's
        next URL or JupyterHub's default (the user's server)."""
        if not milestone:
            return self.get_next_url(user)
        path = self.authenticator.milestone_path.format(milestone=milestone).lstrip("/")
        target = url_path_join(self.hub.base_url, "user-redirect", path)
        return url_path_join(self.hub.base_url, "spawn") + "?next=" + quote(target, safe="/")

    async def validated_claims(self) -> Dict[str, Any]:
        """The launch's id_token, verified and validated (module docstring), or a refusal."""
        auth: CourseLTIAuthenticator = self.authenticator
        validator = LTI13LaunchValidator(parent=self.app)
        args = convert_request_to_dict(self.request.arguments)
        try:
            validator.validate_auth_response(args)
            self._checked(self.check_state)
            state = args["state"]
            if not auth.used.first_use("state:" + str(_deserialize_state(state).get("state_id") or state)):
                refuse(self, 400, "this launch's state was used already: a launch is good for one login (open the "
                       "course link in the LMS again)")
            claims = await asyncio.get_running_loop().run_in_executor(auth.pool, auth.verify_token, args["id_token"])
            validator.validate_id_token(claims)
            validator.validate_azp_claim(claims, auth.client_id)
        except InvalidAudienceError as err:
            refuse(self, 401, "the id_token is not for this hub: %s" % err)
        except ValidationError as err:
            refuse(self, 400, "the id_token is not valid: %s" % err)
        deployment = claims.get(lms.DEPLOYMENT_CLAIM)
        if deployment not in auth.deployment_ids:
            refuse(self, 401, "the launch comes from the deployment %r of the LMS, which is not one of this hub's "
                   "(deployment_ids)" % str(deployment)[:200])
        self._checked(lambda: self.check_nonce(claims))
        if not auth.used.first_use("nonce:" + str(claims["nonce"])):
            refuse(self, 400, "this launch's nonce was used already: a replayed launch (open the course link in the "
                   "LMS again)")
        return claims

    def _checked(self, check: Any) -> None:
        """ltiauthenticator's cookie checks (state, nonce), their HTTPError a logged refusal."""
        try:
            check()
        except web.HTTPError as err:
            refuse(self, err.status_code, err.log_message or "the launch's cookies do not match it")


class CourseLTIAuthenticator(LTI13Authenticator):
    """LTI13Authenticator with the course's roles, names, deployments, replay checks and milestone
    (module docstring)."""

    login_handler = CourseLTILoginHandler
    callback_handler = CourseLTICallbackHandler

    data_dir = Unicode(defaults.DATA_DIR, help="""The hub's data folder: lti-users.json, the LMS identity
        (iss, sub, deployment, AGS line items) of each hub user, is there.""").tag(config=True)
    deployment_ids = Set(Unicode(), help="""The LMS deployments of the tool whose launches are accepted
        (claim https://purl.imsglobal.org/spec/lti/claim/deployment_id; Canvas shows it on the app's
        Deployment ID, Moodle on the tool's Details). Required: a launch of any other is
        refused.""").tag(config=True)
    milestone_parameter = Unicode("milestone", help="""The launch's custom parameter (claim
        https://purl.imsglobal.org/spec/lti/claim/custom) naming the milestone the workbench opens on;
        empty: none.""").tag(config=True)
    milestone_path = Unicode("lab/tree/milestones/{milestone}.md", help="""Where in the student's server
        a launch naming a milestone lands, {milestone} its id (the workbench's ~/milestones holds the
        course's milestone pages).""").tag(config=True)
    ta_roles = ListTrait(Unicode(), list(lms.TA_ROLES), help="""LTI roles that make a TA (a hub admin);
        one ending in * matches every role starting with the rest. Institution roles (e.g.
        http://purl.imsglobal.org/vocab/lis/v2/institution/person#Instructor) are not in it: a
        student of this course who teaches another has that role.""").tag(config=True)
    student_roles = ListTrait(Unicode(), list(lms.STUDENT_ROLES), help="""LTI roles that make a
        student.""").tag(config=True)
    jwks_threads = Integer(2, help="threads fetching the platform's keys and checking signatures").tag(config=True)

    @default("username_key")
    def _the_lms_user_id(self) -> str:
        return "sub"  # never changes; ltiauthenticator's default, email, can

    @default("allow_all")
    def _the_lms_decides(self) -> bool:
        # a launch signed by this class's platform, tool and deployment is who may come in
        return True

    def __init__(self, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        missing = [name for name in REQUIRED if not getattr(self, name)]
        if missing:
            raise ValueError("CourseLTIAuthenticator: %s not set: the platform's and the tool's registration "
                             "(docs/hub.md, \"Logging in from the LMS\")" % ", ".join(missing))
        self.pool = ThreadPoolExecutor(self.jwks_threads, thread_name_prefix="course-lti")
        self.jwks = jwt.PyJWKClient(self.jwks_endpoint, cache_keys=True, timeout=JWKS_TIMEOUT_S)
        validator = LTI13LaunchValidator(parent=self.parent) if self.parent else LTI13LaunchValidator()
        # a nonce or state older than this is refused by the id_token's iat already
        self.used = lms.UsedOnce(validator.max_age + validator.time_leeway + 60)
        self.identities = lms.Identities(self.data_dir)

    def verify_token(self, token: str) -> Dict[str, Any]:
        """The id_token's claims: its signature checked with the platform's key (JWKS), its aud
        one of client_id, its iss the issuer, not expired. Beside the event loop (the JWKS may be
        fetched). ltiauthenticator's ValidationError subclasses for a bad token."""
        try:
            key = self.jwks.get_signing_key_from_jwt(token).key
            return jwt.decode(token, key, algorithms=self.jwks_algorithms, audience=sorted(self.client_id),
                              issuer=self.issuer, options={"require": REQUIRED_CLAIMS})
        except jwt.InvalidAudienceError as err:
            raise InvalidAudienceError(str(err)) from None
        except jwt.PyJWTError as err:
            raise TokenError("%s: %s" % (type(err).__name__, err)) from None

    async def authenticate(self, handler: web.RequestHandler, data: Optional[Dict[str, Any]] = None) -> Dict[str, Any]:
        """The hub user of a validated launch (`data`, its id_token's claims): name, admin (TA)
        or not; refused (403, logged) without a role the hub knows, without a usable name, or
        with a name another LMS user holds."""
        claims = data or {}
        try:
            who = lms.identity_of(claims)
            role = lms.role_of(claims, self.ta_roles, self.student_roles)
            wanted = lms.hub_name(lms.claim_value(claims, self.username_key))
            name = await asyncio.get_running_loop().run_in_executor(self.pool, self.identities.claim, wanted, who)
        except lms.NameTaken as err:
            self.log.warning("LTI user %s of %s would take the hub name of %s of %s", claims.get("sub"),
                             claims.get("iss"), err.holder.sub, err.holder.iss)
            refuse(handler, 403, str(err))
        except lms.Refused as err:
            refuse(handler, 403, str(err))
        if name != wanted:
            self.log.info("LTI user %s of %s keeps the hub name %s (the claim %s now gives %s)",
                          who.sub, who.iss, name, self.username_key, wanted)
        self.log.info("LTI launch: %s (%s of %s) as %s", name, who.sub, who.iss, role)
        return {"name": name, "admin": role == lms.TA,
                "auth_state": {"iss": who.iss, "sub": who.sub, "deployment_id": who.deployment_id, "role": role}}
