"""Debian's chromedriver, spoken to at 127.0.0.1 and never at "localhost".

Selenium's Service looks for the driver at "localhost", a name a minimal Debian (a chroot, a
container without /etc/hosts) cannot resolve; the driver listens on 127.0.0.1 anyway. This
Service names the address itself, so nothing depends on name resolution.
"""
from selenium.webdriver.chrome.service import Service
from selenium.webdriver.common import utils


class LocalService(Service):
    def __init__(self):
        super().__init__('/usr/bin/chromedriver')

    @property
    def service_url(self):
        return f'http://127.0.0.1:{self.port}'

    def is_connectable(self):
        return utils.is_connectable(self.port, host='127.0.0.1')
