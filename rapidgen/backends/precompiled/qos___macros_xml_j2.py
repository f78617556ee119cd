# mypy: ignore-errors
# Template templates/qos/_macros.xml.j2, compiled by Jinja2 3.1.6; do not edit.
# python -m rapidgen.backends.templating --write refreshes it (rapidgen/backends/templating.py).
KEY = "81949811b59eb895021efe85bdb7d23b5ae4383fa7b1545c0075f862ab8782eb"
from jinja2.runtime import LoopContext, Macro, Markup, Namespace, TemplateNotFound, TemplateReference, TemplateRuntimeError, Undefined, escape, identity, internalcode, markup_join, missing, str_join
name = '_macros.xml.j2'

def root(context, missing=missing, environment=environment):
    resolve = context.resolve_or_missing
    undefined = environment.undefined
    concat = environment.concat
    cond_expr_undefined = Undefined
    if 0: yield None
    l_0_locator = l_0_duration = l_0_fastdds_endpoint = l_0_omg_endpoint = l_0_omg_partition = l_0_rti_participant = missing
    try:
        t_1 = environment.tests['none']
    except KeyError:
        @internalcode
        def t_1(*unused):
            raise TemplateRuntimeError("No test named 'none' found.")
    pass
    def macro(l_1_l):
        t_2 = []
        if l_1_l is missing:
            l_1_l = undefined("parameter 'l' was not provided", name='l')
        pass
        if environment.getattr(l_1_l, 'is_any'):
            pass
            t_2.append(
                '<locator/>',
            )
        else:
            pass
            t_2.extend((
                '<locator><',
                escape(environment.finalize(environment.getattr(l_1_l, 'kind'))),
                '><address>',
                escape(environment.finalize(environment.getattr(l_1_l, 'address'))),
                '</address>',
            ))
            if (not t_1(environment.getattr(l_1_l, 'physical_port'))):
                pass
                t_2.extend((
                    '<physical_port>',
                    escape(environment.finalize(environment.getattr(l_1_l, 'physical_port'))),
                    '</physical_port>',
                ))
            if (not t_1(environment.getattr(l_1_l, 'port'))):
                pass
                t_2.extend((
                    '<port>',
                    escape(environment.finalize(environment.getattr(l_1_l, 'port'))),
                    '</port>',
                ))
            t_2.extend((
                '</',
                escape(environment.finalize(environment.getattr(l_1_l, 'kind'))),
                '></locator>',
            ))
        return concat(t_2)
    context.exported_vars.add('locator')
    context.vars['locator'] = l_0_locator = Macro(environment, macro, 'locator', ('l',), False, False, False, context.eval_ctx.autoescape)
    yield '\n'
    def macro(l_1_d):
        t_3 = []
        if l_1_d is missing:
            l_1_d = undefined("parameter 'd' was not provided", name='d')
        pass
        t_3.extend((
            '<sec>',
            escape(environment.finalize(environment.getattr(l_1_d, 'sec'))),
            '</sec><nanosec>',
            escape(environment.finalize(environment.getattr(l_1_d, 'nanosec'))),
            '</nanosec>',
        ))
        return concat(t_3)
    context.exported_vars.add('duration')
    context.vars['duration'] = l_0_duration = Macro(environment, macro, 'duration', ('d',), False, False, False, context.eval_ctx.autoescape)
    yield '\n'
    def macro(l_1_e, l_1_p, l_1_link):
        t_4 = []
        if l_1_e is missing:
            l_1_e = undefined("parameter 'e' was not provided", name='e')
        if l_1_p is missing:
            l_1_p = undefined("parameter 'p' was not provided", name='p')
        if l_1_link is missing:
            l_1_link = None
        pass
        t_4.extend((
            '<topic>\n  <historyQos>\n    <kind>',
            escape(environment.finalize(environment.getattr(l_1_e, 'history_kind'))),
            '</kind>\n',
        ))
        if environment.getattr(l_1_e, 'has_depth'):
            pass
            t_4.extend((
                '    <depth>',
                escape(environment.finalize(environment.getattr(l_1_e, 'history_depth'))),
                '</depth>\n',
            ))
        t_4.append(
            '  </historyQos>\n',
        )
        if environment.getattr(l_1_e, 'limits'):
            pass
            t_4.extend((
                '  <resourceLimitsQos>\n    <max_samples>',
                escape(environment.finalize(environment.getattr(environment.getattr(l_1_e, 'limits'), 'max_samples'))),
                '</max_samples>\n    <max_instances>',
                escape(environment.finalize(environment.getattr(environment.getattr(l_1_e, 'limits'), 'max_instances'))),
                '</max_instances>\n    <max_samples_per_instance>',
                escape(environment.finalize(environment.getattr(environment.getattr(l_1_e, 'limits'), 'max_samples_per_instance'))),
                '</max_samples_per_instance>\n  </resourceLimitsQos>\n',
            ))
        t_4.extend((
            '</topic>\n<qos>\n  <reliability>\n    <kind>',
            escape(environment.finalize(environment.getattr(l_1_e, 'reliability'))),
            '</kind>\n',
        ))
        if (l_1_link and (environment.getattr(l_1_e, 'reliability') == 'RELIABLE')):
            pass
            t_4.extend((
                '    <max_blocking_time>',
                escape(environment.finalize(context.call((undefined(name='duration') if l_0_duration is missing else l_0_duration), environment.getattr(l_1_link, 'max_blocking')))),
                '</max_blocking_time>\n',
            ))
        t_4.extend((
            '  </reliability>\n  <durability>\n    <kind>',
            escape(environment.finalize(environment.getattr(l_1_e, 'durability'))),
            '</kind>\n  </durability>\n',
        ))
        if environment.getattr(l_1_e, 'publish_mode'):
            pass
            t_4.extend((
                '  <publishMode>\n    <kind>',
                escape(environment.finalize(environment.getattr(l_1_e, 'publish_mode'))),
                '</kind>\n  </publishMode>\n',
            ))
        if environment.getattr(l_1_p, 'has_partition'):
            pass
            t_4.extend((
                '  <partition>\n    <names>\n      <name>',
                escape(environment.finalize(environment.getattr(l_1_p, 'partition'))),
                '</name>\n    </names>\n  </partition>\n',
            ))
        t_4.append(
            '</qos>',
        )
        return concat(t_4)
    context.exported_vars.add('fastdds_endpoint')
    context.vars['fastdds_endpoint'] = l_0_fastdds_endpoint = Macro(environment, macro, 'fastdds_endpoint', ('e', 'p', 'link'), False, False, False, context.eval_ctx.autoescape)
    yield '\n'
    def macro(l_1_e):
        t_5 = []
        if l_1_e is missing:
            l_1_e = undefined("parameter 'e' was not provided", name='e')
        pass
        if environment.getattr(l_1_e, 'reliability'):
            pass
            t_5.extend((
                '<reliability>\n  <kind>',
                escape(environment.finalize(environment.getattr(l_1_e, 'reliability'))),
                '</kind>\n</reliability>\n',
            ))
        if environment.getattr(l_1_e, 'durability'):
            pass
            t_5.extend((
                '<durability>\n  <kind>',
                escape(environment.finalize(environment.getattr(l_1_e, 'durability'))),
                '</kind>\n</durability>\n',
            ))
        if environment.getattr(l_1_e, 'has_history'):
            pass
            t_5.extend((
                '<history>\n  <kind>',
                escape(environment.finalize(environment.getattr(l_1_e, 'history_kind'))),
                '</kind>\n',
            ))
            if environment.getattr(l_1_e, 'has_depth'):
                pass
                t_5.extend((
                    '  <depth>',
                    escape(environment.finalize(environment.getattr(l_1_e, 'history_depth'))),
                    '</depth>\n',
                ))
            t_5.append(
                '</history>\n',
            )
        if environment.getattr(l_1_e, 'publish_mode'):
            pass
            t_5.extend((
                '<publish_mode>\n  <kind>',
                escape(environment.finalize(environment.getattr(l_1_e, 'publish_mode'))),
                '</kind>\n</publish_mode>\n',
            ))
        return concat(t_5)
    context.exported_vars.add('omg_endpoint')
    context.vars['omg_endpoint'] = l_0_omg_endpoint = Macro(environment, macro, 'omg_endpoint', ('e',), False, False, False, context.eval_ctx.autoescape)
    yield '\n'
    def macro(l_1_name):
        t_6 = []
        if l_1_name is missing:
            l_1_name = undefined("parameter 'name' was not provided", name='name')
        pass
        t_6.extend((
            '<partition>\n  <name>\n    <element>',
            escape(environment.finalize(l_1_name)),
            '</element>\n  </name>\n</partition>',
        ))
        return concat(t_6)
    context.exported_vars.add('omg_partition')
    context.vars['omg_partition'] = l_0_omg_partition = Macro(environment, macro, 'omg_partition', ('name',), False, False, False, context.eval_ctx.autoescape)
    yield '\n'
    def macro(l_1_p):
        t_7 = []
        if l_1_p is missing:
            l_1_p = undefined("parameter 'p' was not provided", name='p')
        pass
        if environment.getattr(l_1_p, 'has_mask'):
            pass
            t_7.extend((
                '<transport_builtin>\n  <mask>',
                escape(environment.finalize(environment.getattr(l_1_p, 'builtin_mask'))),
                '</mask>\n</transport_builtin>\n',
            ))
        if environment.getattr(l_1_p, 'sets_discovery'):
            pass
            t_7.append(
                '<discovery>\n  <initial_peers>\n',
            )
            for l_2_peer in environment.getattr(l_1_p, 'initial_peers'):
                _loop_vars = {}
                pass
                t_7.extend((
                    '    <element>',
                    escape(environment.finalize(l_2_peer)),
                    '</element>\n',
                ))
            l_2_peer = missing
            t_7.append(
                '  </initial_peers>\n',
            )
            if environment.getattr(l_1_p, 'has_multicast_receive'):
                pass
                t_7.append(
                    '  <multicast_receive_addresses>\n',
                )
                for l_2_a in environment.getattr(l_1_p, 'multicast_receive'):
                    _loop_vars = {}
                    pass
                    t_7.extend((
                        '    <element>',
                        escape(environment.finalize(l_2_a)),
                        '</element>\n',
                    ))
                l_2_a = missing
                t_7.append(
                    '  </multicast_receive_addresses>\n',
                )
            else:
                pass
                t_7.append(
                    '  <multicast_receive_addresses/>\n',
                )
            t_7.append(
                '</discovery>\n',
            )
        if environment.getattr(l_1_p, 'type_code_off'):
            pass
            t_7.append(
                '<resource_limits>\n  <type_code_max_serialized_length>0</type_code_max_serialized_length>\n  <type_object_max_serialized_length>0</type_object_max_serialized_length>\n</resource_limits>\n',
            )
        if environment.getattr(l_1_p, 'has_ports'):
            pass
            t_7.extend((
                '<wire_protocol>\n  <rtps_well_known_ports>\n    <port_base>',
                escape(environment.finalize(environment.getattr(environment.getattr(l_1_p, 'ports'), 'base'))),
                '</port_base>\n    <domain_id_gain>',
                escape(environment.finalize(environment.getattr(environment.getattr(l_1_p, 'ports'), 'domain_gain'))),
                '</domain_id_gain>\n    <participant_id_gain>',
                escape(environment.finalize(environment.getattr(environment.getattr(l_1_p, 'ports'), 'participant_gain'))),
                '</participant_id_gain>\n    <builtin_multicast_port_offset>',
                escape(environment.finalize(environment.getattr(environment.getattr(l_1_p, 'ports'), 'd0'))),
                '</builtin_multicast_port_offset>\n    <builtin_unicast_port_offset>',
                escape(environment.finalize(environment.getattr(environment.getattr(l_1_p, 'ports'), 'd1'))),
                '</builtin_unicast_port_offset>\n    <user_multicast_port_offset>',
                escape(environment.finalize(environment.getattr(environment.getattr(l_1_p, 'ports'), 'd2'))),
                '</user_multicast_port_offset>\n    <user_unicast_port_offset>',
                escape(environment.finalize(environment.getattr(environment.getattr(l_1_p, 'ports'), 'd3'))),
                '</user_unicast_port_offset>\n  </rtps_well_known_ports>\n</wire_protocol>\n',
            ))
        if environment.getattr(l_1_p, 'has_properties'):
            pass
            t_7.append(
                '<property>\n  <value>\n',
            )
            for l_2_prop in environment.getattr(l_1_p, 'properties'):
                _loop_vars = {}
                pass
                t_7.extend((
                    '    <element>\n      <name>',
                    escape(environment.finalize(environment.getattr(l_2_prop, 'name'))),
                    '</name>\n      <value>',
                    escape(environment.finalize(environment.getattr(l_2_prop, 'value'))),
                    '</value>\n    </element>\n',
                ))
            l_2_prop = missing
            t_7.append(
                '  </value>\n</property>\n',
            )
        return concat(t_7)
    context.exported_vars.add('rti_participant')
    context.vars['rti_participant'] = l_0_rti_participant = Macro(environment, macro, 'rti_participant', ('p',), False, False, False, context.eval_ctx.autoescape)

blocks = {}
debug_info = '3=18&4=23&7=32&17=60&18=67&21=76&24=87&25=90&26=94&29=100&31=104&32=106&33=108&39=113&40=116&41=120&45=125&47=128&49=132&52=135&55=139&62=149&63=154&65=158&68=161&70=165&73=168&75=172&76=175&77=179&81=185&83=189&88=196&91=203&96=210&97=215&99=219&102=222&105=227&106=232&109=239&111=244&112=249&120=264&126=269&129=273&130=275&131=277&132=279&133=281&134=283&135=285&139=288&142=293&144=298&145=300'
