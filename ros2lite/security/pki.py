"""Keys, certificates and S/MIME signatures as sros2 makes them, with ``cryptography``.

* keys: ECDSA on prime256v1 (DDS-Security 9.3.1 asks for it), PKCS#8 PEM, unencrypted;
* the CA: self-signed, ``CN=sros2CA``, basicConstraints CA (path length 1, critical);
* an enclave: ``CN=<enclave name>``, signed by the CA, basicConstraints not-CA;
* all valid from now for 3650 days, signed with SHA-256;
* documents (governance, permissions): detached, text-mode S/MIME (``multipart/signed``,
  ``micalg="sha-256"``), which ``openssl smime -verify`` checks against the CA, and so does
  :func:`verify_document` (OpenSSL's own PKCS#7 verification, as ``cryptography`` binds it).

Importing this module loads ``cryptography``; nothing on a hot path does.
"""

from __future__ import annotations

import datetime
import email
from pathlib import Path

from cryptography import x509
from cryptography.exceptions import InternalError, InvalidSignature
from cryptography.hazmat.primitives import hashes, serialization
from cryptography.hazmat.primitives.asymmetric import ec, rsa
from cryptography.hazmat.primitives.serialization import pkcs7

from ros2lite.security.errors import KeystoreError, PolicyError
from ros2lite.security.files import read_bytes, write_file, write_private

__all__ = [
    'CA_COMMON_NAME',
    'SigningKey',
    'certificate_problem',
    'load_certificate',
    'load_private_key',
    'new_ca',
    'new_identity',
    'read_signed',
    'sign_document',
    'verify_document',
    'write_certificate',
    'write_private_key',
]

CA_COMMON_NAME = 'sros2CA'
# a key that can sign both certificates and S/MIME documents; sros2 makes ECDSA ones
SigningKey = ec.EllipticCurvePrivateKey | rsa.RSAPrivateKey
VALIDITY = datetime.timedelta(days=3650)


def _build(
    subject: str, *, ca: bool, issuer: x509.Name | None = None, issuer_key: SigningKey | None = None
) -> tuple[x509.Certificate, ec.EllipticCurvePrivateKey]:
    key = ec.generate_private_key(ec.SECP256R1())
    name = x509.Name([x509.NameAttribute(x509.oid.NameOID.COMMON_NAME, subject)])
    now = datetime.datetime.now(datetime.timezone.utc)
    constraints = (
        x509.BasicConstraints(ca=True, path_length=1)
        if ca
        else x509.BasicConstraints(ca=False, path_length=None)
    )
    cert = (
        x509.CertificateBuilder()
        .issuer_name(issuer or name)
        .subject_name(name)
        .serial_number(x509.random_serial_number())
        .not_valid_before(now)
        .not_valid_after(now + VALIDITY)
        .public_key(key.public_key())
        .add_extension(constraints, critical=ca)
        .sign(issuer_key or key, hashes.SHA256())
    )
    return cert, key


def new_ca(
    common_name: str = CA_COMMON_NAME,
) -> tuple[x509.Certificate, ec.EllipticCurvePrivateKey]:
    """A fresh self-signed CA certificate and its key."""
    return _build(common_name, ca=True)


def new_identity(
    common_name: str, ca_cert: x509.Certificate, ca_key: SigningKey
) -> tuple[x509.Certificate, ec.EllipticCurvePrivateKey]:
    """A fresh certificate for ``common_name`` (an enclave), signed by the CA."""
    return _build(common_name, ca=False, issuer=ca_cert.subject, issuer_key=ca_key)


def write_private_key(key: SigningKey, path: Path) -> None:
    """PKCS#8 PEM in a new file readable by its owner only (see ``files.write_private``)."""
    data = key.private_bytes(
        serialization.Encoding.PEM,
        serialization.PrivateFormat.PKCS8,
        serialization.NoEncryption(),
    )
    write_private(path, data)


def write_certificate(cert: x509.Certificate, path: Path) -> None:
    """Write a certificate as PEM."""
    write_file(path, cert.public_bytes(serialization.Encoding.PEM))


def load_certificate(path: Path) -> x509.Certificate:
    """A PEM certificate; unreadable or malformed files give a one-line KeystoreError."""
    try:
        return x509.load_pem_x509_certificate(path.read_bytes())
    except (OSError, ValueError) as exc:
        raise KeystoreError(f"cannot load certificate '{path}': {exc}") from None


def load_private_key(path: Path) -> SigningKey:
    """A PEM private key (unencrypted, as sros2 writes them) of a kind that signs."""
    try:
        key = serialization.load_pem_private_key(path.read_bytes(), password=None)
    except (OSError, ValueError, TypeError) as exc:
        raise KeystoreError(f"cannot load private key '{path}': {exc}") from None
    if not isinstance(key, (ec.EllipticCurvePrivateKey, rsa.RSAPrivateKey)):
        raise KeystoreError(f"cannot load private key '{path}': not an ECDSA or RSA key")
    return key


def sign_document(cert: x509.Certificate, key: SigningKey, content: bytes) -> bytes:
    """``content`` wrapped in a detached, text-mode S/MIME signature (sros2's .p7s)."""
    return (
        pkcs7.PKCS7SignatureBuilder()
        .set_data(content)
        .add_signer(cert, key, hashes.SHA256())
        .sign(
            serialization.Encoding.SMIME,
            [pkcs7.PKCS7Options.Text, pkcs7.PKCS7Options.DetachedSignature],
        )
    )


def certificate_problem(
    cert: x509.Certificate, ca: x509.Certificate, enclave: str, now: datetime.datetime
) -> str | None:
    """Why an enclave's certificate would be refused (one phrase), None when it is usable:
    issued by the keystore's identity CA, naming the enclave, valid now."""
    what = f'the certificate of enclave {enclave}'
    try:
        cert.verify_directly_issued_by(ca)
    except (ValueError, TypeError, InvalidSignature):
        return f"{what} is not issued by the keystore's identity CA"
    names = cert.subject.get_attributes_for_oid(x509.oid.NameOID.COMMON_NAME)
    common_name = str(names[0].value) if names else ''
    if common_name != enclave:
        return f'{what} names CN={common_name}, not {enclave}'
    if now > cert.not_valid_after_utc:
        return f'{what} expired on {cert.not_valid_after_utc:%Y-%m-%d %H:%M} UTC'
    if now < cert.not_valid_before_utc:
        return f'{what} is not valid before {cert.not_valid_before_utc:%Y-%m-%d %H:%M} UTC'
    return None


def _text_mode(content: bytes) -> bytes:
    """The content as text-mode S/MIME signs it: a text/plain part with CRLF line ends."""
    lines = content.replace(b'\r\n', b'\n').replace(b'\n', b'\r\n')
    return b'Content-Type: text/plain\r\n\r\n' + lines


def verify_document(ca: x509.Certificate, signed: bytes, content: bytes) -> bool:
    """Whether ``signed`` (a detached S/MIME .p7s) is a signature of ``content`` by ``ca``
    or a certificate it issued (``openssl smime -verify -CAfile ca -content``).

    ``cryptography`` exposes OpenSSL's PKCS#7 verification only in its test-support
    bindings; without them nothing can be verified, and that is an error, never a pass."""
    try:
        from cryptography.hazmat.bindings._rust import test_support
    except ImportError:  # pragma: no cover - a cryptography built without them
        pkcs7_verify = None
    else:
        pkcs7_verify = getattr(test_support, 'pkcs7_verify', None)
    if pkcs7_verify is None:  # pragma: no cover - cryptography < 43
        raise KeystoreError('this cryptography package cannot verify S/MIME signatures')
    try:
        pkcs7_verify(serialization.Encoding.SMIME, signed, _text_mode(content), [ca], [])
    except (ValueError, TypeError, InternalError):
        return False
    return document_signer_is(ca, signed)


def document_signer_is(ca: x509.Certificate, signed: bytes) -> bool:
    """Whether the CA itself signed: every certificate the signature carries is ``ca``.

    OpenSSL's check above passes a signature by *any* certificate ``ca`` issued, and in
    sros2's default keystore every enclave's certificate is one, so an enclave could re-sign
    its own permissions. DDS Security asks for the permissions CA's own signature; OpenSSL
    looks for the signer among the certificates the signature carries and those it is given
    (``ca`` alone), so when it carries no other, the signer can only be the CA."""
    try:
        carried = pkcs7.load_der_pkcs7_certificates(_signature_der(signed))
    except ValueError:
        return False
    return all(cert == ca for cert in carried)


def _carried_other_than(ca: x509.Certificate, signed: bytes) -> str | None:
    """The subject of a certificate other than ``ca`` that the signature carries, if any."""
    try:
        carried = pkcs7.load_der_pkcs7_certificates(_signature_der(signed))
    except ValueError:
        return None
    return next((c.subject.rfc4514_string() for c in carried if c != ca), None)


def _signature_der(signed: bytes) -> bytes:
    """The PKCS#7 structure (DER) inside an S/MIME multipart/signed document."""
    message = email.message_from_bytes(signed)
    for part in message.walk():
        if part.get_content_type() in _SIGNATURE_TYPES:
            payload = part.get_payload(decode=True)
            if isinstance(payload, bytes) and payload:
                return payload
    raise ValueError('no PKCS#7 signature part')


_SIGNATURE_TYPES = ('application/pkcs7-signature', 'application/x-pkcs7-signature')


def read_signed(document: Path, signature: Path, ca_certificate: Path, what: str) -> bytes:
    """``document``'s bytes once ``signature`` proves the permissions CA signed exactly
    them; else a one-line PolicyError naming ``what`` (e.g. ``permissions of enclave /a``)."""
    content = read_bytes(document, what)
    if not signature.is_file():
        raise PolicyError(f'{what}: {signature.name} (its signature) is missing')
    signed = read_bytes(signature, f'{what} signature')
    ca = load_certificate(ca_certificate)
    if not verify_document(ca, signed, content):
        other = _carried_other_than(ca, signed)
        if other is not None:
            raise PolicyError(
                f'{what}: {signature.name} is signed by {other}, not by the permissions CA'
            )
        raise PolicyError(
            f'{what}: {document.name} does not match its signature {signature.name} '
            'by the permissions CA'
        )
    return content
