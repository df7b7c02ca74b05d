"""The files `pkg create` writes, as text.

The layout is the one `ros2 pkg create` produces (so colcon builds the package on a ROS
machine and every tutorial step applies), in our own words. Every value placed into a file
was validated by :mod:`ros2lite.pkg.create` or is quoted here for the file's language: XML
escaping in package.xml, Python string literals in setup.py.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from xml.sax.saxutils import escape, quoteattr

__all__ = ['PackageSpec']


@dataclass(frozen=True)
class PackageSpec:
    """Everything a new package is made from (validated by :func:`create.create_package`)."""

    name: str
    build_type: str = 'ament_cmake'
    package_format: int = 3
    description: str = 'TODO: Package description'
    license: str = 'TODO: License declaration'
    maintainer_name: str = 'user'
    maintainer_email: str = 'user@todo.todo'
    dependencies: tuple[str, ...] = ()
    node_name: str | None = None
    library_name: str | None = None
    version: str = '0.0.0'
    buildtool_dependencies: tuple[str, ...] = field(default=())
    test_dependencies: tuple[str, ...] = field(default=())


def _py(value: str) -> str:
    """A Python string literal for `value` (repr quotes and escapes whatever it holds)."""
    return repr(value)


def _lines(tag: str, names: Sequence[str]) -> str:
    if not names:
        return ''
    return ''.join(f'  <{tag}>{escape(n)}</{tag}>\n' for n in names) + '\n'


def package_xml(spec: PackageSpec) -> str:
    """package.xml in the requested format, build type exported."""
    fmt = spec.package_format
    return (
        '<?xml version="1.0"?>\n'
        f'<?xml-model href="http://download.ros.org/schema/package_format{fmt}.xsd" '
        'schematypens="http://www.w3.org/2001/XMLSchema"?>\n'
        f'<package format="{fmt}">\n'
        f'  <name>{escape(spec.name)}</name>\n'
        f'  <version>{escape(spec.version)}</version>\n'
        f'  <description>{escape(spec.description)}</description>\n'
        f'  <maintainer email={quoteattr(spec.maintainer_email)}>'
        f'{escape(spec.maintainer_name)}</maintainer>\n'
        f'  <license>{escape(spec.license)}</license>\n'
        '\n'
        + _lines('buildtool_depend', spec.buildtool_dependencies)
        + _lines('depend', spec.dependencies)
        + _lines('test_depend', spec.test_dependencies)
        + '  <export>\n'
        f'    <build_type>{escape(spec.build_type)}</build_type>\n'
        '  </export>\n'
        '</package>\n'
    )


# -- ament_python -------------------------------------------------------------------------------


def setup_py(spec: PackageSpec) -> str:
    """setup.py: the package, its ament index marker and manifest, its console scripts."""
    scripts = ''
    if spec.node_name:
        entry = f'{spec.node_name} = {spec.name}.{spec.node_name}:main'
        scripts = f'            {_py(entry)},\n'
    return (
        'from setuptools import find_packages, setup\n'
        '\n'
        f'package_name = {_py(spec.name)}\n'
        '\n'
        'setup(\n'
        '    name=package_name,\n'
        f'    version={_py(spec.version)},\n'
        "    packages=find_packages(exclude=['test']),\n"
        '    data_files=[\n'
        "        ('share/ament_index/resource_index/packages',\n"
        "            ['resource/' + package_name]),\n"
        "        ('share/' + package_name, ['package.xml']),\n"
        '    ],\n'
        "    install_requires=['setuptools'],\n"
        '    zip_safe=True,\n'
        f'    maintainer={_py(spec.maintainer_name)},\n'
        f'    maintainer_email={_py(spec.maintainer_email)},\n'
        f'    description={_py(spec.description)},\n'
        f'    license={_py(spec.license)},\n'
        '    extras_require={\n'
        "        'test': [\n"
        "            'pytest',\n"
        '        ],\n'
        '    },\n'
        '    entry_points={\n'
        "        'console_scripts': [\n"
        f'{scripts}'
        '        ],\n'
        '    },\n'
        ')\n'
    )


def setup_cfg(spec: PackageSpec) -> str:
    """setup.cfg: console scripts go to lib/<package>, where ros2 run looks for them."""
    return (
        '[develop]\n'
        f'script_dir=$base/lib/{spec.name}\n'
        '[install]\n'
        f'install_scripts=$base/lib/{spec.name}\n'
    )


def python_node(spec: PackageSpec) -> str:
    """The empty executable a new package starts with."""
    return (
        'def main():\n'
        f'    print({_py("Hi from " + spec.name + ".")})\n'
        '\n'
        '\n'
        "if __name__ == '__main__':\n"
        '    main()\n'
    )


def test_copyright() -> str:
    """The ament_copyright check (skipped until the sources carry copyright notices)."""
    return (
        'from ament_copyright.main import main\n'
        'import pytest\n'
        '\n'
        '\n'
        '# Remove the skip once every source file carries a copyright and license notice.\n'
        "@pytest.mark.skip(reason='No copyright header has been placed in the source files.')\n"
        '@pytest.mark.copyright\n'
        '@pytest.mark.linter\n'
        'def test_copyright():\n'
        "    rc = main(argv=['.', 'test'])\n"
        "    assert rc == 0, 'Found errors'\n"
    )


def test_flake8() -> str:
    """The ament_flake8 style check."""
    return (
        'from ament_flake8.main import main_with_errors\n'
        'import pytest\n'
        '\n'
        '\n'
        '@pytest.mark.flake8\n'
        '@pytest.mark.linter\n'
        'def test_flake8():\n'
        '    rc, errors = main_with_errors(argv=[])\n'
        '    assert rc == 0, \\\n'
        "        'Found %d code style errors / warnings:\\n' % len(errors) + \\\n"
        "        '\\n'.join(errors)\n"
    )


def test_pep257() -> str:
    """The ament_pep257 docstring check."""
    return (
        'from ament_pep257.main import main\n'
        'import pytest\n'
        '\n'
        '\n'
        '@pytest.mark.linter\n'
        '@pytest.mark.pep257\n'
        'def test_pep257():\n'
        "    rc = main(argv=['.', 'test'])\n"
        "    assert rc == 0, 'Found code style errors / warnings'\n"
    )


# -- ament_cmake / cmake ------------------------------------------------------------------------

_NO_DEPS = '# list further dependencies here, e.g.\n# find_package(<dependency> REQUIRED)\n'


def _find_packages(deps: Sequence[str]) -> str:
    return ''.join(f'find_package({d} REQUIRED)\n' for d in deps) if deps else _NO_DEPS


def _ament_deps(target: str, deps: Sequence[str]) -> str:
    if not deps:
        return ''
    quoted = ''.join(f'  "{d}"\n' for d in deps)
    return f'ament_target_dependencies(\n  {target}\n{quoted})\n'


def _cmake_head(project: str) -> str:
    """What every generated CMakeLists.txt starts with, up to finding its dependencies."""
    return (
        f'cmake_minimum_required(VERSION 3.8)\n{project}\n\n'
        'if(CMAKE_COMPILER_IS_GNUCXX OR CMAKE_CXX_COMPILER_ID MATCHES "Clang")\n'
        '  add_compile_options(-Wall -Wextra -Wpedantic)\n'
        'endif()\n\n'
        '# find dependencies\n'
    )


def ament_cmake_lists(spec: PackageSpec) -> str:
    """CMakeLists.txt of an ament_cmake package (executable and/or library if asked)."""
    deps = spec.dependencies
    out = [_cmake_head(f'project({spec.name})'), 'find_package(ament_cmake REQUIRED)\n']
    if spec.library_name:
        out.append('find_package(ament_cmake_ros REQUIRED)\n')
    out.append(_find_packages(deps))
    if spec.library_name:
        lib = spec.library_name
        out += [
            '\n',
            f'add_library({lib} src/{lib}.cpp)\n',
            f'add_library({spec.name}::{lib} ALIAS {lib})\n',
            f'target_compile_features({lib} PUBLIC c_std_99 cxx_std_17)  # C99 and C++17\n',
            f'target_include_directories({lib} PUBLIC\n',
            '  $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>\n',
            '  $<INSTALL_INTERFACE:include/${PROJECT_NAME}>)\n',
            _ament_deps(lib, deps),
            '\n',
            '# the visibility macros export symbols while this library itself is built\n',
            f'target_compile_definitions({lib} PRIVATE "{spec.name.upper()}_BUILDING_LIBRARY")\n',
            '\n',
            'install(\n',
            '  DIRECTORY include/\n',
            '  DESTINATION include/${PROJECT_NAME}\n',
            ')\n',
            'install(\n',
            f'  TARGETS {lib}\n',
            '  EXPORT export_${PROJECT_NAME}\n',
            '  ARCHIVE DESTINATION lib\n',
            '  LIBRARY DESTINATION lib\n',
            '  RUNTIME DESTINATION bin\n',
            ')\n',
        ]
    if spec.node_name:
        node = spec.node_name
        out += [
            '\n',
            f'add_executable({node} src/{node}.cpp)\n',
            f'target_include_directories({node} PUBLIC\n',
            '  $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>\n',
            '  $<INSTALL_INTERFACE:include/${PROJECT_NAME}>)\n',
        ]
        if spec.library_name:
            out.append(f'target_link_libraries({node} {spec.library_name})\n')
        else:
            out.append(
                f'target_compile_features({node} PUBLIC c_std_99 cxx_std_17)  # C99 and C++17\n'
            )
            out.append(_ament_deps(node, deps))
        out += [
            '\n',
            f'install(TARGETS {node}\n',
            '  DESTINATION lib/${PROJECT_NAME})\n',
        ]
    out += [
        '\n',
        'if(BUILD_TESTING)\n',
        '  find_package(ament_lint_auto REQUIRED)\n',
        '  # skip the copyright linter until every source file carries a license notice\n',
        '  set(ament_cmake_copyright_FOUND TRUE)\n',
        '  # skip cpplint until the package is in a git repository with license notices\n',
        '  set(ament_cmake_cpplint_FOUND TRUE)\n',
        '  ament_lint_auto_find_test_dependencies()\n',
        'endif()\n',
    ]
    if spec.library_name:
        out += [
            '\n',
            'ament_export_include_directories(\n',
            '  "include/${PROJECT_NAME}"\n',
            ')\n',
            'ament_export_libraries(\n',
            f'  {spec.library_name}\n',
            ')\n',
            'ament_export_targets(\n',
            '  export_${PROJECT_NAME}\n',
            ')\n',
        ]
    out += ['\n', 'ament_package()\n']
    return ''.join(out)


def _plain_target_settings(target: str, includes: str) -> str:
    """A plain cmake target's language standards and include directories (its own
    include/ and its dependencies')."""
    return (
        f'target_compile_features({target} PUBLIC c_std_99 cxx_std_17)  # C99 and C++17\n'
        f'target_include_directories({target} PUBLIC\n'
        '  $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>\n'
        '  $<INSTALL_INTERFACE:include>\n'
        f'{includes})\n'
    )


def cmake_lists(spec: PackageSpec) -> str:
    """CMakeLists.txt of a plain cmake package, with its package config files."""
    name = spec.name
    deps = spec.dependencies
    out = [_cmake_head(f'project({name} VERSION {spec.version})'), _find_packages(deps)]
    # what is installed and exported: the library, then the node
    targets = [t for t in (spec.library_name, spec.node_name) if t]
    link = ''.join(f' ${{{d}_LIBRARIES}}' for d in deps)
    includes = ''.join(f'  PUBLIC ${{{d}_INCLUDE_DIRS}}\n' for d in deps)
    if spec.library_name:
        lib = spec.library_name
        out += [
            '\n',
            f'add_library({lib} SHARED src/{lib}.cpp)\n',
            f'add_library({name}::{lib} ALIAS {lib})\n',
            _plain_target_settings(lib, includes),
            f'target_link_libraries({lib}{link})\n' if deps else '',
            f'target_compile_definitions({lib} PRIVATE "{name.upper()}_BUILDING_LIBRARY")\n',
            '\n',
            'install(DIRECTORY include/ DESTINATION include)\n',
        ]
    if spec.node_name:
        node = spec.node_name
        out += [
            '\n',
            f'add_executable({node} src/{node}.cpp)\n',
            _plain_target_settings(node, includes),
        ]
        if spec.library_name:
            out.append(f'target_link_libraries({node} {spec.library_name})\n')
        elif deps:
            out.append(f'target_link_libraries({node}{link})\n')
    if targets:
        out += [
            '\n',
            f'install(TARGETS {" ".join(targets)}\n',
            f'  EXPORT export_{name}\n',
            '  ARCHIVE DESTINATION lib\n',
            '  LIBRARY DESTINATION lib\n',
            '  RUNTIME DESTINATION lib/${PROJECT_NAME})\n',
            f'install(EXPORT export_{name}\n',
            f'  NAMESPACE {name}::\n',
            '  DESTINATION share/${PROJECT_NAME}/cmake)\n',
        ]
    out += [
        '\n',
        '# the package config files find_package() reads\n',
        f'configure_file({name}Config.cmake.in\n',
        f'  "${{PROJECT_BINARY_DIR}}/{name}Config.cmake" @ONLY)\n',
        f'configure_file({name}ConfigVersion.cmake.in\n',
        f'  "${{PROJECT_BINARY_DIR}}/{name}ConfigVersion.cmake" @ONLY)\n',
        'install(FILES\n',
        f'  "${{PROJECT_BINARY_DIR}}/{name}Config.cmake"\n',
        f'  "${{PROJECT_BINARY_DIR}}/{name}ConfigVersion.cmake"\n',
        '  DESTINATION share/${PROJECT_NAME}/cmake)\n',
    ]
    return ''.join(out)


def cmake_config_in(spec: PackageSpec) -> str:
    """<name>Config.cmake.in: what find_package(<name>) loads."""
    name = spec.name
    return (
        f'# {name} package configuration, filled in by configure_file()\n'
        f'get_filename_component({name}_CMAKE_DIR "${{CMAKE_CURRENT_LIST_FILE}}" PATH)\n'
        f'if(EXISTS "${{{name}_CMAKE_DIR}}/export_{name}.cmake")\n'
        f'  include("${{{name}_CMAKE_DIR}}/export_{name}.cmake")\n'
        'endif()\n'
        f'set({name}_FOUND TRUE)\n'
    )


def cmake_config_version_in(spec: PackageSpec) -> str:
    """<name>ConfigVersion.cmake.in: the version find_package() compares against."""
    return (
        'set(PACKAGE_VERSION "@PROJECT_VERSION@")\n'
        '\n'
        '# any version at least the requested one is compatible\n'
        'if(PACKAGE_VERSION VERSION_LESS PACKAGE_FIND_VERSION)\n'
        '  set(PACKAGE_VERSION_COMPATIBLE FALSE)\n'
        'else()\n'
        '  set(PACKAGE_VERSION_COMPATIBLE TRUE)\n'
        '  if(PACKAGE_FIND_VERSION STREQUAL PACKAGE_VERSION)\n'
        '    set(PACKAGE_VERSION_EXACT TRUE)\n'
        '  endif()\n'
        'endif()\n'
    )


def cpp_node(spec: PackageSpec) -> str:
    """The empty C++ executable."""
    return (
        '#include <cstdio>\n'
        '\n'
        'int main(int argc, char ** argv)\n'
        '{\n'
        '  (void) argc;\n'
        '  (void) argv;\n'
        '\n'
        f'  printf("hello world {spec.name} package\\n");\n'
        '  return 0;\n'
        '}\n'
    )


def _class_name(library: str) -> str:
    return ''.join(part.capitalize() for part in library.split('_') if part)


def cpp_header(spec: PackageSpec) -> str:
    """include/<name>/<library>.hpp: one empty class."""
    assert spec.library_name is not None
    guard = f'{spec.name}__{spec.library_name}_HPP_'.upper()
    cls = _class_name(spec.library_name)
    return (
        f'#ifndef {guard}\n'
        f'#define {guard}\n'
        '\n'
        f'#include "{spec.name}/visibility_control.h"\n'
        '\n'
        f'namespace {spec.name}\n'
        '{\n'
        '\n'
        f'class {cls}\n'
        '{\n'
        'public:\n'
        f'  {cls}();\n'
        '\n'
        f'  virtual ~{cls}();\n'
        '};\n'
        '\n'
        f'}}  // namespace {spec.name}\n'
        '\n'
        f'#endif  // {guard}\n'
    )


def cpp_library(spec: PackageSpec) -> str:
    """src/<library>.cpp: the class's empty definitions."""
    assert spec.library_name is not None
    cls = _class_name(spec.library_name)
    return (
        f'#include "{spec.name}/{spec.library_name}.hpp"\n'
        '\n'
        f'namespace {spec.name}\n'
        '{\n'
        '\n'
        f'{cls}::{cls}()\n'
        '{\n'
        '}\n'
        '\n'
        f'{cls}::~{cls}()\n'
        '{\n'
        '}\n'
        '\n'
        f'}}  // namespace {spec.name}\n'
    )


def visibility_control(spec: PackageSpec) -> str:
    """include/<name>/visibility_control.h: symbol export macros for shared libraries."""
    p = spec.name.upper()
    return (
        f'#ifndef {p}__VISIBILITY_CONTROL_H_\n'
        f'#define {p}__VISIBILITY_CONTROL_H_\n'
        '\n'
        '// Symbols are hidden unless marked: <PKG>_PUBLIC marks what the library exports.\n'
        '// <PKG>_BUILDING_LIBRARY is defined while the library itself is compiled.\n'
        '#if defined _WIN32 || defined __CYGWIN__\n'
        '  #ifdef __GNUC__\n'
        f'    #define {p}_EXPORT __attribute__ ((dllexport))\n'
        f'    #define {p}_IMPORT __attribute__ ((dllimport))\n'
        '  #else\n'
        f'    #define {p}_EXPORT __declspec(dllexport)\n'
        f'    #define {p}_IMPORT __declspec(dllimport)\n'
        '  #endif\n'
        f'  #ifdef {p}_BUILDING_LIBRARY\n'
        f'    #define {p}_PUBLIC {p}_EXPORT\n'
        '  #else\n'
        f'    #define {p}_PUBLIC {p}_IMPORT\n'
        '  #endif\n'
        f'  #define {p}_PUBLIC_TYPE {p}_PUBLIC\n'
        f'  #define {p}_LOCAL\n'
        '#else\n'
        f'  #define {p}_EXPORT __attribute__ ((visibility("default")))\n'
        f'  #define {p}_IMPORT\n'
        '  #if __GNUC__ >= 4\n'
        f'    #define {p}_PUBLIC __attribute__ ((visibility("default")))\n'
        f'    #define {p}_LOCAL  __attribute__ ((visibility("hidden")))\n'
        '  #else\n'
        f'    #define {p}_PUBLIC\n'
        f'    #define {p}_LOCAL\n'
        '  #endif\n'
        f'  #define {p}_PUBLIC_TYPE\n'
        '#endif\n'
        '\n'
        f'#endif  // {p}__VISIBILITY_CONTROL_H_\n'
    )
